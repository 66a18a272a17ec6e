// Raw float32 cubes with a JSON sidecar: round trip, the bytes on disk, the documented sidecar,
// wrong sizes and bad sidecars.

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "formats.hpp" // detail::write_raw_slabs
#include "geotandem/core/error.hpp"
#include "geotandem/volume/io.hpp"
#include "io_fixtures.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;
using namespace geotandem;
using namespace geotandem::volume;
using geotandem::testing::ScratchDir;
using geotandem::volume::testing::formula;
using geotandem::volume::testing::formula_cube;
using geotandem::volume::testing::formula_samples;
using geotandem::volume::testing::probe_boxes;
using geotandem::volume::testing::read_bytes;
using geotandem::volume::testing::sample_geometry;
using geotandem::volume::testing::write_bytes;
using json = nlohmann::json;

namespace {

FormatError format_error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const FormatError& e) {
    return e;
  }
  ADD_FAILURE() << "no FormatError";
  return FormatError("none");
}

// A geometry whose doubles have no short decimal form, so that a sidecar that rounds shows.
Geometry awkward_geometry() {
  Geometry g = sample_geometry({5, 6, 40});
  g.inline0 = 0.1 + 0.2;
  g.crossline_step = 1.0 / 3.0;
  g.z0 = -17.125;
  g.dz = 0.7;
  g.z_unit = SampleUnit::metres;
  g.affine.xj = std::nextafter(-6.25, 0.0);
  return g;
}

TEST(Raw, RoundTripKeepsEveryGeometryFieldAndSample) {
  ScratchDir dir;
  const Geometry g = awkward_geometry();
  auto cube = formula_cube(g);
  const std::string path = dir.file("cube.raw");
  write_volume(*cube, path);
  ASSERT_TRUE(fs::exists(path + ".json"));
  EXPECT_EQ(detect_format(path), "raw");

  auto back = open_volume(path);
  EXPECT_EQ(back->format(), "raw");
  EXPECT_EQ(back->source(), path);
  EXPECT_EQ(back->geometry(), g); // exact, every field
  const auto whole = back->read(g.bounds());
  EXPECT_EQ(whole, cube->samples());
  for (const Box& box : probe_boxes(g.shape))
    EXPECT_EQ(back->read(box), formula_samples(box)) << box.to_string();
}

// The copy of an input for reads by blocks (Volume::use_block_copy) writes raw files slab by slab
// along any axis: every axis and thickness, the last slab short or not, gives the bytes that
// write_volume gives, and a cancelled write leaves no file.
TEST(Raw, SlabsAlongEveryAxisWriteTheSameFile) {
  ScratchDir dir;
  const Geometry g = sample_geometry({5, 7, 11});
  auto cube = formula_cube(g);
  const std::string reference = dir.file("reference.raw");
  write_volume(*cube, reference);
  const std::string expected = read_bytes(reference);
  ASSERT_EQ(expected.size(), 5u * 7u * 11u * sizeof(float));
  NullProgress quiet;
  for (int axis = 0; axis < 3; ++axis)
    for (std::int64_t thickness : {1, 2, 3, 4, 100}) {
      const std::string path = dir.file("slabs" + std::to_string(axis) + "-" + std::to_string(thickness) + ".raw");
      detail::write_raw_slabs(*cube, path, axis, thickness, "test", quiet, {});
      EXPECT_EQ(read_bytes(path), expected) << "axis " << axis << ", thickness " << thickness;
      EXPECT_EQ(open_volume(path)->geometry(), g);
    }
  CancelToken cancel;
  cancel.cancel();
  const std::string cancelled = dir.file("cancelled.raw");
  EXPECT_THROW(detail::write_raw_slabs(*cube, cancelled, 2, 3, "test", quiet, cancel), Cancelled);
  EXPECT_FALSE(fs::exists(cancelled));
  EXPECT_FALSE(fs::exists(cancelled + ".json"));
  EXPECT_THROW(detail::write_raw_slabs(*cube, dir.file("bad.raw"), 3, 1, "test", quiet, {}), InvalidArgument);
}

TEST(Raw, BoxesOfACubeLargerThanOneReadSpan) {
  // 11 MB: a sample slice and a crossline slab need several merged reads (8 MiB each at most).
  ScratchDir dir;
  const Geometry g = sample_geometry({30, 90, 1000});
  const std::string path = dir.file("large.raw");
  write_volume(*formula_cube(g), path);
  auto volume = open_volume(path);
  for (const Box& box :
       {Box{{0, 0, 500}, {30, 90, 501}}, Box{{0, 40, 0}, {30, 41, 1000}}, Box{{3, 10, 100}, {25, 80, 164}}, g.bounds()})
    EXPECT_EQ(volume->read(box), formula_samples(box)) << box.to_string();
}

TEST(Raw, DataFileIsLittleEndianFloat32InCOrder) {
  ScratchDir dir;
  const Geometry g = sample_geometry({3, 4, 5});
  const std::string path = dir.file("cube.raw");
  write_volume(*formula_cube(g), path);
  const std::string bytes = read_bytes(path);
  ASSERT_EQ(bytes.size(), g.sample_count() * 4);
  // Sample (2, 3, 4) is the last; (1, 2, 3) sits at ((1 * 4 + 2) * 5 + 3) floats.
  for (auto [i, j, k] : {std::array<int, 3>{0, 0, 0}, {1, 2, 3}, {2, 3, 4}}) {
    const std::size_t at = ((static_cast<std::size_t>(i) * 4 + j) * 5 + k) * 4;
    std::uint32_t bits = 0;
    for (int b = 3; b >= 0; --b)
      bits = bits << 8 | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(b)]);
    float value = 0;
    std::memcpy(&value, &bits, 4);
    EXPECT_EQ(value, formula(i, j, k)) << i << j << k;
  }
  const json sidecar = json::parse(read_bytes(path + ".json"));
  EXPECT_EQ(sidecar.at("format"), "geotandem-raw");
  EXPECT_EQ(sidecar.at("version"), 1);
  EXPECT_EQ(sidecar.at("shape"), json::array({3, 4, 5}));
  EXPECT_EQ(sidecar.at("geometry").at("dz"), 2.0);
  EXPECT_EQ(sidecar.at("geometry").at("z_unit"), "ms");
}

// The example sidecar of docs/formats-segy-raw.md, written by hand, must open.
const char* documented_sidecar = R"({
  "format": "geotandem-raw",
  "version": 1,
  "dtype": "float32",
  "byte_order": "little",
  "order": "C",
  "axes": ["inline", "crossline", "sample"],
  "shape": [2, 3, 4],
  "geometry": {
    "inline0": 1000, "inline_step": 2,
    "crossline0": 300, "crossline_step": 1,
    "z0": 0, "dz": 4, "z_unit": "ms",
    "affine": {"x0": 431250.0, "xi": 12.5, "xj": 0.0, "y0": 6712040.0, "yi": 0.0, "yj": 12.5}
  }
}
)";

std::string make_raw(const ScratchDir& dir, const std::string& sidecar, std::size_t samples = 24) {
  const std::string path = dir.file("hand.raw");
  write_bytes(path, std::string(samples * 4, '\0'));
  write_bytes(path + ".json", sidecar);
  return path;
}

TEST(Raw, HandWrittenSidecarOpens) {
  ScratchDir dir;
  const std::string path = make_raw(dir, documented_sidecar);
  auto volume = open_volume(path);
  const Geometry& g = volume->geometry();
  EXPECT_EQ(g.shape, (Index3{2, 3, 4}));
  EXPECT_EQ(g.inline0, 1000);
  EXPECT_EQ(g.affine.yj, 12.5);
  EXPECT_EQ(volume->read(g.bounds()), std::vector<float>(24, 0.0f));
}

TEST(Raw, WrongSizeNamesBothSizesAndBothFiles) {
  ScratchDir dir;
  for (std::size_t samples : {23u, 25u, 0u}) {
    const std::string path = make_raw(dir, documented_sidecar, samples);
    FormatError e = format_error_of([&] { open_volume(path); });
    const std::string message = e.what();
    EXPECT_EQ(e.context().file, path);
    EXPECT_NE(message.find(path + ".json"), std::string::npos) << message;
    EXPECT_NE(message.find(std::to_string(samples * 4) + " bytes"), std::string::npos) << message;
    EXPECT_NE(message.find("96 bytes"), std::string::npos) << message;
  }
}

TEST(Raw, BadSidecarNamesTheFileAndTheKey) {
  ScratchDir dir;
  json good = json::parse(documented_sidecar);
  struct Case {
    std::string name;
    std::function<void(json&)> edit;
    std::string expected; // in the message
  };
  const std::vector<Case> cases = {
      {"unknown top-level key", [](json& d) { d["colour"] = "red"; }, "unknown key 'colour'"},
      {"unknown nested key", [](json& d) { d["geometry"]["affine"]["zz"] = 1; }, "'geometry.affine.zz'"},
      {"missing key", [](json& d) { d["geometry"].erase("dz"); }, "missing key 'geometry.dz'"},
      {"missing shape", [](json& d) { d.erase("shape"); }, "missing key 'shape'"},
      {"wrong type", [](json& d) { d["geometry"]["dz"] = "4"; }, "'geometry.dz' must be a number"},
      {"bad shape",
       [](json& d) {
         d["shape"] = json::array({2, 0, 4});
       },
       "'shape'"},
      {"short shape",
       [](json& d) {
         d["shape"] = json::array({2, 3});
       },
       "'shape'"},
      {"other format tag", [](json& d) { d["format"] = "envi"; }, "'format'"},
      {"future version", [](json& d) { d["version"] = 2; }, "version 2"},
      {"big endian", [](json& d) { d["byte_order"] = "big"; }, "'byte_order'"},
      {"bad unit", [](json& d) { d["geometry"]["z_unit"] = "s"; }, "z_unit"},
      {"zero dz", [](json& d) { d["geometry"]["dz"] = 0; }, "dz"},
      {"not an object", [](json& d) { d["geometry"]["affine"] = 3; }, "'geometry.affine'"},
  };
  for (const Case& c : cases) {
    json doc = good;
    c.edit(doc);
    const std::string path = make_raw(dir, doc.dump(2));
    FormatError e = format_error_of([&] { open_volume(path); });
    const std::string message = e.what();
    EXPECT_EQ(e.context().file, path + ".json") << c.name;
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.name << ": " << message;
  }
}

TEST(Raw, InvalidJsonGivesLineAndColumn) {
  ScratchDir dir;
  const std::string path = make_raw(dir, "{\n  \"format\": \"geotandem-raw\",\n  \"version\": 1,,\n}\n");
  FormatError e = format_error_of([&] { open_volume(path); });
  EXPECT_EQ(e.context().file, path + ".json");
  ASSERT_TRUE(e.context().line.has_value());
  EXPECT_EQ(*e.context().line, 3);
  ASSERT_TRUE(e.context().column.has_value());
  EXPECT_EQ(*e.context().column, 16);
}

} // namespace
