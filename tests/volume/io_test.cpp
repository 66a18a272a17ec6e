// Format detection and bad input through the public io API: signatures of every kind, unknown and
// missing files, boxes outside the cube, NaN and infinite samples, overwrite protection,
// cancellation.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <thread>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/io.hpp"
#include "io_fixtures.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;
using namespace geotandem;
using namespace geotandem::volume;
using geotandem::testing::ScratchDir;
using geotandem::volume::testing::formula_cube;
using geotandem::volume::testing::formula_samples;
using geotandem::volume::testing::message_of;
using geotandem::volume::testing::read_bytes;
using geotandem::volume::testing::sample_geometry;
using geotandem::volume::testing::write_bytes;

namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::string padded(std::string head, std::size_t size = 4096) {
  head.resize(size, '\0');
  return head;
}

// ---- Detection ----------------------------------------------------------------------------------

TEST(Detect, EveryFormatFromItsSignatureNotItsName) {
  ScratchDir dir;
  // Extensions are deliberately unhelpful where the format does not depend on them.
  write_bytes(dir.file("classic.dat"), padded(std::string("CDF\x01", 4)));
  write_bytes(dir.file("offset64.dat"), padded(std::string("CDF\x02", 4)));
  write_bytes(dir.file("nc4.nc"), padded("\x89HDF\r\n\x1a\n"));
  write_bytes(dir.file("plain.h5"), padded("\x89HDF\r\n\x1a\n"));
  write_bytes(dir.file("little.dat"), padded(std::string("II*\0", 4)));
  write_bytes(dir.file("big.dat"), padded(std::string("MM\0*", 4)));
  write_bytes(dir.file("bigtiff.dat"), padded(std::string("II+\0", 4)));
  write_bytes(dir.file("envi.img"), padded("anything"));
  write_bytes(dir.file("envi.img.hdr"), "ENVI\nsamples = 2\n");
  write_bytes(dir.file("envi2.bin"), padded("anything"));
  write_bytes(dir.file("envi2.hdr"), "ENVI\nsamples = 2\n");
  for (const char* marker : {".zgroup", ".zarray", "zarr.json"}) {
    fs::create_directories(dir.file(std::string("store") + marker));
    write_bytes(dir.file(std::string("store") + marker + "/" + marker), "{}");
  }
  auto cube = formula_cube(sample_geometry({2, 3, 10}));
  write_volume(*cube, dir.file("cube.sgy"));
  fs::rename(dir.file("cube.sgy"), dir.file("cube.dat"));
  write_volume(*cube, dir.file("cube.raw"));

  const std::vector<std::pair<std::string, std::string>> expected = {
      {"classic.dat", "netCDF-4"}, {"offset64.dat", "netCDF-4"}, {"nc4.nc", "netCDF-4"},     {"plain.h5", "HDF5"},
      {"little.dat", "GeoTIFF"},   {"big.dat", "GeoTIFF"},       {"bigtiff.dat", "GeoTIFF"}, {"envi.img", "ENVI"},
      {"envi2.bin", "ENVI"},       {"store.zgroup", "Zarr"},     {"store.zarray", "Zarr"},   {"storezarr.json", "Zarr"},
      {"cube.dat", "SEG-Y"},       {"cube.raw", "raw"},
  };
  for (const auto& [name, format] : expected)
    EXPECT_EQ(detect_format(dir.file(name)), format) << name;
  // The SEG-Y cube renamed to .dat opens as SEG-Y.
  EXPECT_EQ(open_volume(dir.file("cube.dat"))->read(cube->geometry().bounds()), cube->samples());
}

TEST(Detect, ASignatureWinsOverAJsonFileBesideIt) {
  // Other tools leave FILE.json metadata beside cubes; only files without a signature of their own
  // are raw.
  ScratchDir dir;
  write_bytes(dir.file("survey.nc"), padded("\x89HDF\r\n\x1a\n"));
  write_bytes(dir.file("survey.nc.json"), "{\"source\": \"some other tool\"}");
  write_bytes(dir.file("slices.tif"), padded(std::string("II*\0", 4)));
  write_bytes(dir.file("slices.tif.json"), "{}");
  EXPECT_EQ(detect_format(dir.file("survey.nc")), "netCDF-4");
  EXPECT_EQ(detect_format(dir.file("slices.tif")), "GeoTIFF");
}

TEST(Detect, RandomBytesAreAnUnknownFormatNamingTheFile) {
  ScratchDir dir;
  std::mt19937 random(20240611);
  for (std::size_t size : {0u, 3u, 5000u}) {
    std::string bytes(size, '\0');
    for (char& c : bytes)
      c = static_cast<char>(random() & 0xFF);
    const std::string path = dir.file("noise" + std::to_string(size) + ".bin");
    write_bytes(path, bytes);
    std::string message = message_of<FormatError>([&] { detect_format(path); });
    EXPECT_TRUE(contains(message, "unknown format")) << message;
    EXPECT_TRUE(contains(message, path)) << message;
    message = message_of<FormatError>([&] { open_volume(path); });
    EXPECT_TRUE(contains(message, "unknown format")) << message;
  }
}

TEST(Detect, MissingFileIsAnIoError) {
  ScratchDir dir;
  const std::string path = dir.file("nowhere.sgy");
  EXPECT_TRUE(contains(message_of<IoError>([&] { detect_format(path); }), path));
  EXPECT_TRUE(contains(message_of<IoError>([&] { open_volume(path); }), path));
}

TEST(Detect, DirectoryThatIsNotZarrIsAFormatError) {
  ScratchDir dir;
  fs::create_directories(dir.file("folder"));
  write_bytes(dir.file("folder/readme.txt"), "not a store");
  const std::string path = dir.file("folder");
  EXPECT_TRUE(contains(message_of<FormatError>([&] { detect_format(path); }), path));
  EXPECT_TRUE(contains(message_of<FormatError>([&] { open_volume(path); }), "Zarr"));
}

// ---- Boxes --------------------------------------------------------------------------------------

TEST(BadInput, BoxOutsideTheCubeNamesTheBoxAndTheShape) {
  ScratchDir dir;
  const Geometry g = sample_geometry({7, 9, 50});
  auto cube = formula_cube(g);
  write_volume(*cube, dir.file("cube.raw"));
  write_volume(*cube, dir.file("cube.sgy"));
  for (const std::string name : {"cube.raw", "cube.sgy"}) {
    auto volume = open_volume(dir.file(name));
    for (const Box& box : {Box{{0, 0, 0}, {8, 9, 50}}, Box{{-1, 0, 0}, {2, 2, 2}}, Box{{0, 0, 49}, {1, 1, 51}},
                           Box{{3, 3, 3}, {3, 5, 5}}}) {
      const std::string message = message_of<InvalidArgument>([&] { volume->read(box); });
      EXPECT_TRUE(contains(message, box.to_string())) << message;
      EXPECT_TRUE(contains(message, "[0:7, 0:9, 0:50]")) << message;
      EXPECT_TRUE(contains(message, dir.file(name))) << message;
    }
    std::vector<float> small(10);
    EXPECT_THROW(volume->read(Box{{0, 0, 0}, {1, 1, 11}}, small), InvalidArgument);
  }
}

TEST(BadInput, RawAndSegyVolumesReadFromSeveralThreadsAtOnce) {
  ScratchDir dir;
  const Geometry g = sample_geometry({7, 9, 50});
  auto cube = formula_cube(g);
  write_volume(*cube, dir.file("cube.raw"));
  write_volume(*cube, dir.file("cube.sgy"));
  for (const std::string name : {"cube.raw", "cube.sgy"}) {
    auto volume = open_volume(dir.file(name));
    std::vector<std::thread> threads;
    std::vector<int> wrong(4, 0);
    for (int t = 0; t < 4; ++t)
      threads.emplace_back([&, t] {
        for (int rep = 0; rep < 20; ++rep) {
          const Box box{{t, (rep + t) % 5, rep}, {t + 3, (rep + t) % 5 + 4, rep + 25}};
          if (volume->read(box) != formula_samples(box)) ++wrong[static_cast<std::size_t>(t)];
        }
      });
    for (auto& thread : threads)
      thread.join();
    EXPECT_EQ(wrong, std::vector<int>(4, 0)) << name;
  }
}

// ---- NaN and infinite samples -------------------------------------------------------------------

TEST(BadInput, NanAndInfiniteSamplesFollowThePolicy) {
  ScratchDir dir;
  const Geometry g = sample_geometry({7, 9, 50});
  auto cube = formula_cube(g);
  const Box all = g.bounds();
  cube->samples()[all.offset({2, 3, 4})] = std::numeric_limits<float>::quiet_NaN();
  cube->samples()[all.offset({5, 6, 7})] = -std::numeric_limits<float>::infinity();
  write_volume(*cube, dir.file("holes.raw"));
  write_volume(*cube, dir.file("holes.sgy"));

  for (const std::string name : {"holes.raw", "holes.sgy"}) {
    const std::string path = dir.file(name);
    auto strict = open_volume(path);
    std::string message = message_of<DataError>([&] { strict->read(all); });
    EXPECT_TRUE(contains(message, path)) << message;
    EXPECT_TRUE(contains(message, "NaN")) << message;
    EXPECT_TRUE(contains(message, "(2, 3, 4)")) << message;
    message = message_of<DataError>([&] { strict->read(Box{{4, 4, 0}, {7, 9, 50}}); });
    EXPECT_TRUE(contains(message, "infinite")) << message;
    EXPECT_TRUE(contains(message, "(5, 6, 7)")) << message;
    // Boxes without bad samples read normally.
    const Box clean{{0, 0, 0}, {2, 9, 50}};
    EXPECT_EQ(strict->read(clean), formula_samples(clean));

    OpenOptions fill;
    fill.nan_policy = NanPolicy::fill;
    fill.fill_value = -999.0f;
    auto filled = open_volume(path, fill)->read(all);
    std::vector<float> expected = formula_samples(all);
    expected[all.offset({2, 3, 4})] = -999.0f;
    expected[all.offset({5, 6, 7})] = -999.0f;
    EXPECT_EQ(filled, expected);
  }
  // A null given when opening (a SEG-Y or raw cube cannot declare one) is missing as NaN is.
  for (const std::string name : {"holes.raw", "holes.sgy"}) {
    const std::string path = dir.file(name);
    OpenOptions given;
    given.no_data = geotandem::volume::testing::formula(1, 2, 3);
    auto strict = open_volume(path, given);
    const std::string message = message_of<DataError>([&] { strict->read(Box{{0, 0, 0}, {2, 9, 50}}); });
    EXPECT_TRUE(contains(message, "no-data sample at index (1, 2, 3)")) << message;
    EXPECT_TRUE(contains(message, "the no-data value given")) << message;
    bool listed = false;
    for (const auto& d : strict->format_details())
      listed = listed || d.key == "no_data_given";
    EXPECT_TRUE(listed) << name;
    given.nan_policy = NanPolicy::fill;
    auto filled = open_volume(path, given)->read(all);
    std::vector<float> expected = formula_samples(all);
    for (const Index3 at : {Index3{1, 2, 3}, Index3{2, 3, 4}, Index3{5, 6, 7}})
      expected[all.offset(at)] = std::numeric_limits<float>::lowest();
    EXPECT_EQ(filled, expected) << name;
  }
  EXPECT_EQ(parse_nan_policy("fill"), NanPolicy::fill);
  EXPECT_EQ(parse_nan_policy("error"), NanPolicy::error);
  EXPECT_THROW(parse_nan_policy("ignore"), InvalidArgument);
}

// ---- Writing ------------------------------------------------------------------------------------

TEST(BadInput, WriteVolumeNeverOverwritesUnlessAsked) {
  ScratchDir dir;
  const Geometry g = sample_geometry({3, 4, 10});
  auto first = formula_cube(g);
  auto second = formula_cube(g);
  for (float& v : second->samples())
    v = -v;
  for (const std::string name : {"cube.raw", "cube.sgy"}) {
    const std::string path = dir.file(name);
    write_volume(*first, path);
    const std::string before = read_bytes(path);
    EXPECT_TRUE(contains(message_of<IoError>([&] { write_volume(*second, path); }), path));
    EXPECT_EQ(read_bytes(path), before);
    EXPECT_EQ(open_volume(path)->read(g.bounds()), first->samples());

    WriteOptions overwrite;
    overwrite.overwrite = true;
    write_volume(*second, path, overwrite);
    EXPECT_EQ(open_volume(path)->read(g.bounds()), second->samples());
  }
  // An unknown extension is refused before the existing file is touched, even with overwrite.
  const std::string keep = dir.file("keep.xyz");
  write_bytes(keep, "precious");
  WriteOptions overwrite;
  overwrite.overwrite = true;
  EXPECT_TRUE(contains(message_of<InvalidArgument>([&] { write_volume(*first, keep, overwrite); }), ".xyz"));
  EXPECT_EQ(read_bytes(keep), "precious");
  WriteOptions no_chunk;
  no_chunk.chunk = 0;
  EXPECT_THROW(write_volume(*first, dir.file("c.raw"), no_chunk), InvalidArgument);
  EXPECT_THROW(write_volume(*first, dir.file("no/such/dir/c.raw")), IoError);
  EXPECT_THROW(write_volume(*first, dir.file("no/such/dir/c.sgy")), IoError);
}

class CountingProgress final : public Progress {
public:
  void begin(const std::string&, std::uint64_t total, const std::string&) override { total_ = total; }
  void update(std::uint64_t done) override { last_ = done; }
  void end() override { ended_ = true; }
  std::uint64_t total_ = 0, last_ = 0;
  bool ended_ = false;
};

TEST(BadInput, CancelledWriteLeavesNoOutputAndProgressReachesTheEnd) {
  ScratchDir dir;
  auto cube = formula_cube(sample_geometry({4, 3, 10}));
  for (const std::string name : {"cube.raw", "cube.sgy"}) {
    CancelToken cancel;
    cancel.cancel();
    EXPECT_THROW(write_volume(*cube, dir.file(name), {}, nullptr, cancel), Cancelled);
    EXPECT_FALSE(fs::exists(dir.file(name))) << name;
    EXPECT_FALSE(fs::exists(dir.file(name) + ".json")) << name;

    CountingProgress progress;
    write_volume(*cube, dir.file(name), {}, &progress);
    EXPECT_EQ(progress.total_, 4u);
    EXPECT_EQ(progress.last_, 4u);
    EXPECT_TRUE(progress.ended_);
  }
}

} // namespace
