// SEG-Y as delivered (issue 54, part 4): line numbers and coordinates at any byte with a declared
// type, the coordinate scalar, revision 2 files, unsorted files read through a trace index and
// duplicated traces refused. The files are written with segyio's Python module by
// segy_delivered.py, which also writes segyio's own reading of each file (every trace's samples
// and header fields): geotandem's reading must equal it.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/crs.hpp"
#include "geotandem/volume/io.hpp"
#include "io_fixtures.hpp"
#include "scratch.hpp"
#include "test_paths.hpp"

namespace geotandem::volume::testing {
namespace {

using geotandem::testing::ScratchDir;
using nlohmann::json;

// Writes the case's file with segyio and returns segyio's reading of it.
json delivered(const std::string& name, const std::string& path) {
  const std::string oracle = path + ".segyio.json"; // not PATH.json, which would be a raw sidecar
  const std::string command = "/usr/bin/python3 '" + test_paths::source() + "/tests/volume/segy_delivered.py' " + name +
                              " '" + path + "' '" + oracle + "'";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream in(oracle);
  return json::parse(in);
}

// The options that say where the case put its fields.
SegyOptions options_of(const json& oracle) {
  SegyOptions o;
  o.inline_byte = oracle["il"][0];
  o.inline_type = parse_header_type(oracle["il"][1]);
  o.crossline_byte = oracle["xl"][0];
  o.crossline_type = parse_header_type(oracle["xl"][1]);
  o.x_byte = oracle["x"][0];
  o.x_type = parse_header_type(oracle["x"][1]);
  o.y_byte = oracle["y"][0];
  o.y_type = parse_header_type(oracle["y"][1]);
  return o;
}

std::string detail(const Volume& v, const std::string& key) {
  for (const auto& d : v.format_details())
    if (d.key == key) return d.value;
  return {};
}

// Shape, line numbers, every sample and every trace's coordinates as segyio read them; the
// coordinates scaled by `factor` (the oracle applies the file's scalar; an override changes it).
void expect_segyio_reading(const Volume& volume, const json& oracle, double factor = 1.0) {
  std::set<int> inlines, crosslines;
  for (const auto& t : oracle["traces"]) {
    inlines.insert(static_cast<int>(t["inline"].get<double>()));
    crosslines.insert(static_cast<int>(t["crossline"].get<double>()));
  }
  const Geometry& g = volume.geometry();
  const int ns = oracle["samples"];
  ASSERT_EQ(g.shape[0], static_cast<std::int64_t>(inlines.size()));
  ASSERT_EQ(g.shape[1], static_cast<std::int64_t>(crosslines.size()));
  ASSERT_EQ(g.shape[2], ns);
  const int il_step = *std::next(inlines.begin()) - *inlines.begin();
  const int xl_step = *std::next(crosslines.begin()) - *crosslines.begin();
  EXPECT_EQ(g.inline0, *inlines.begin());
  EXPECT_EQ(g.inline_step, il_step);
  EXPECT_EQ(g.crossline0, *crosslines.begin());
  EXPECT_EQ(g.crossline_step, xl_step);
  const std::vector<float> cube = volume.read(g.bounds());
  for (const auto& t : oracle["traces"]) {
    const auto i = static_cast<std::int64_t>((t["inline"].get<double>() - g.inline0) / il_step);
    const auto j = static_cast<std::int64_t>((t["crossline"].get<double>() - g.crossline0) / xl_step);
    const auto& samples = t["samples"];
    for (int k = 0; k < ns; ++k)
      ASSERT_EQ(cube[static_cast<std::size_t>((i * g.shape[1] + j) * ns + k)], samples[k].get<float>())
          << "trace " << t["trace"] << " sample " << k;
    const auto xy = g.affine.apply(static_cast<double>(i), static_cast<double>(j));
    EXPECT_NEAR(xy[0], t["x"].get<double>() * factor, 1e-6 * std::abs(t["x"].get<double>() * factor))
        << "trace " << t["trace"];
    EXPECT_NEAR(xy[1], t["y"].get<double>() * factor, 1e-6 * std::abs(t["y"].get<double>() * factor))
        << "trace " << t["trace"];
  }
}

struct Case {
  const char* name;
  const char* sorting; // the start of the "sorting" detail
};

class SegyDelivered : public ::testing::TestWithParam<Case> {};

TEST_P(SegyDelivered, ReadsAsSegyioDoes) {
  ScratchDir dir;
  const std::string path = dir.file(std::string(GetParam().name) + ".sgy");
  const json oracle = delivered(GetParam().name, path);
  OpenOptions options;
  options.segy = options_of(oracle);
  auto volume = open_volume(path, options);
  expect_segyio_reading(*volume, oracle);
  EXPECT_EQ(detail(*volume, "sorting").rfind(GetParam().sorting, 0), 0u) << detail(*volume, "sorting");
  EXPECT_EQ(detail(*volume, "inline_byte"), std::to_string(options.segy.inline_byte));
  EXPECT_EQ(detail(*volume, "inline_type"), to_string(options.segy.inline_type));
  const std::string where = detail(*volume, "coordinate_fields");
  EXPECT_NE(where.find("CDP X at byte " + std::to_string(options.segy.x_byte) + " (" + to_string(options.segy.x_type)),
            std::string::npos)
      << where;
  EXPECT_NE(where.find("scalar from byte 71 of each trace (" + std::to_string(oracle["scalar"].get<int>()) +
                       " in the first trace"),
            std::string::npos)
      << where;
}

INSTANTIATE_TEST_SUITE_P(Cases, SegyDelivered,
                         ::testing::Values(Case{"lines_221_225", "inline-sorted"},
                                           Case{"lines_9_13_int16", "inline-sorted"},
                                           Case{"float_221_225", "inline-sorted"}, Case{"ibm_9_13", "inline-sorted"},
                                           Case{"unsorted", "unsorted: read through a trace index of 42 bins"},
                                           Case{"unsorted_221", "unsorted"}, Case{"revision_2", "inline-sorted"},
                                           Case{"revision_2_extensions", "unsorted"}),
                         [](const auto& test) { return std::string(test.param.name); });

TEST(SegyDeliveredRevision, RevisionAndExtendedHeadersAreReported) {
  ScratchDir dir;
  const std::string path = dir.file("rev2.sgy");
  const json oracle = delivered("revision_2", path);
  EXPECT_EQ(oracle["revision"], 512); // segyio reads 0x0200
  auto volume = open_volume(path);
  const std::string revision = detail(*volume, "revision");
  EXPECT_EQ(revision.rfind("2.0 (binary header bytes 3501-3502); 2 extended textual headers", 0), 0u) << revision;

  const std::string extended = dir.file("ext.sgy");
  const json with_extensions = delivered("revision_2_extensions", extended);
  OpenOptions options;
  options.segy = options_of(with_extensions);
  auto v = open_volume(extended, options);
  EXPECT_NE(detail(*v, "revision").find("2 trace header extensions of 240 bytes per trace"), std::string::npos)
      << detail(*v, "revision");
  // A rev 1 file says so.
  const std::string rev1 = dir.file("rev1.sgy");
  delivered("lines_9_13_int16", rev1);
  OpenOptions int16;
  int16.segy = options_of(delivered("lines_9_13_int16", rev1));
  EXPECT_EQ(detail(*open_volume(rev1, int16), "revision").rfind("0.0", 0), 0u);
}

// The measurement system (binary header bytes 3255-3256) is reported, and a file in feet without a
// CRS is warned about: its x, y and volumes would otherwise be labelled metres without a word. A
// CRS given (in US survey feet here) is the unit used, and the warning goes.
TEST(SegyDeliveredUnits, FeetInTheBinaryHeaderAreReportedAndWarnedWithoutACrs) {
  ScratchDir dir;
  const std::string path = dir.file("feet.sgy");
  const json oracle = delivered("feet", path);
  EXPECT_EQ(oracle["measurement"], 2); // as segyio reads it
  OpenOptions options;
  options.segy = options_of(oracle);
  auto volume = open_volume(path, options);
  EXPECT_EQ(detail(*volume, "measurement"), "feet (binary header bytes 3255-3256 = 2)");
  const std::vector<std::string> warnings = open_warnings(*volume);
  ASSERT_EQ(
      std::count_if(warnings.begin(), warnings.end(),
                    [](const std::string& w) { return w.find("the binary header says feet") != std::string::npos; }),
      1)
      << ::testing::PrintToString(warnings);
  Crs feet; // as parse_crs("EPSG:2227") gives it, without loading GDAL here
  feet.name = "NAD83 / California zone 3 (ftUS)";
  feet.code = "EPSG:2227";
  feet.wkt = "PROJCRS[\"NAD83 / California zone 3 (ftUS)\"]";
  feet.unit = "ftUS";
  feet.metres_per_unit = 1200.0 / 3937.0;
  std::shared_ptr<const Volume> given = with_crs(std::move(volume), feet);
  EXPECT_EQ(given->geometry().crs.unit, "ftUS");
  for (const auto& w : open_warnings(*given))
    EXPECT_EQ(w.find("the binary header says feet"), std::string::npos) << w;
  EXPECT_EQ(detail(*given, "measurement"), "feet (binary header bytes 3255-3256 = 2)");
  // A file that says nothing says so.
  const std::string plain = dir.file("plain.sgy");
  OpenOptions o;
  o.segy = options_of(delivered("unsorted", plain));
  EXPECT_EQ(detail(*open_volume(plain, o), "measurement"), "not given (binary header bytes 3255-3256 = 0)");
}

// The scalar given for every trace replaces the one each header holds (0 here): 10 multiplies,
// -100 divides, 0 means 1.
TEST(SegyDeliveredScalar, AnOverrideReplacesTheHeadersScalar) {
  ScratchDir dir;
  const std::string path = dir.file("scalar.sgy");
  const json oracle = delivered("lines_9_13_int16", path);
  for (const auto& [scalar, factor] : {std::pair{10, 10.0}, {-100, 0.01}, {0, 1.0}, {1, 1.0}}) {
    OpenOptions options;
    options.segy = options_of(oracle);
    options.segy.coordinate_scalar = scalar;
    auto volume = open_volume(path, options);
    expect_segyio_reading(*volume, oracle, factor);
    EXPECT_NE(detail(*volume, "coordinate_fields").find("scalar " + std::to_string(scalar) + " given for every trace"),
              std::string::npos)
        << detail(*volume, "coordinate_fields");
  }
}

TEST(SegyDeliveredBroken, ADuplicatedTraceIsRefusedNamingBothTraces) {
  ScratchDir dir;
  const std::string path = dir.file("duplicated.sgy");
  const json oracle = delivered("duplicated", path);
  // segy_delivered.py puts trace 17 in trace 5's bin.
  EXPECT_EQ(oracle["traces"][5]["inline"], oracle["traces"][17]["inline"]);
  EXPECT_EQ(oracle["traces"][5]["crossline"], oracle["traces"][17]["crossline"]);
  try {
    open_volume(path);
    ADD_FAILURE() << "a duplicated trace was read";
  } catch (const DataError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("traces 5 and 17 both hold inline " +
                           std::to_string(oracle["traces"][5]["inline"].get<int>()) + ", crossline " +
                           std::to_string(oracle["traces"][5]["crossline"].get<int>()) +
                           " (trace header bytes 189/193)"),
              std::string::npos)
        << message;
    EXPECT_EQ(e.exit_code(), 5); // a user's data error, not an internal one
  }
}

// Line numbers read at the declared type that are no whole numbers: the file, the trace and the
// byte are named. Fields past the header's end are refused before the file is read.
TEST(SegyDeliveredBroken, WrongTypesAndPositionsAreNamed) {
  ScratchDir dir;
  const std::string path = dir.file("ints.sgy");
  const json oracle = delivered("lines_221_225", path);
  OpenOptions options;
  options.segy = options_of(oracle);
  options.segy.inline_type = HeaderType::ieee; // integers read as floats: tiny denormals
  const std::string message = message_of<FormatError>([&] { open_volume(path, options); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("trace 0 holds"), std::string::npos) << message;
  EXPECT_NE(message.find("as its inline number (trace header byte 221, ieee): not a whole number"), std::string::npos)
      << message;

  OpenOptions past = {};
  past.segy = options_of(oracle);
  past.segy.x_byte = 238; // 4 bytes from 238 end at 241
  const std::string outside = message_of<InvalidArgument>([&] { open_volume(path, past); });
  EXPECT_NE(outside.find("the CDP X field at byte 238 (int32, 4 bytes) lies outside the 240-byte trace header"),
            std::string::npos)
      << outside;
  past.segy.x_byte = 181;
  past.segy.crossline_byte = 223; // overlaps 221-224
  EXPECT_THROW(open_volume(path, past), InvalidArgument);
}

// The same file read with the common defaults finds no grid and says where else to look.
TEST(SegyDeliveredBroken, LinesElsewhereThanDeclaredAreNotInvented) {
  ScratchDir dir;
  const std::string path = dir.file("221.sgy");
  delivered("lines_221_225", path);
  const std::string message = message_of<FormatError>([&] { open_volume(path); });
  EXPECT_NE(message.find("189/193"), std::string::npos) << message;
  EXPECT_NE(message.find("--inline-byte"), std::string::npos) << message;
}

} // namespace
} // namespace geotandem::volume::testing
