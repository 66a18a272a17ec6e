// `geotandem info` and `extract` on SEG-Y as delivered (little-endian 16-bit integers, line
// numbers at bytes 9/21), written through segyio, as real child processes.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <map>

#include "geotandem/volume/io.hpp"
#include "geotandem/volume/volume.hpp"
#include "scratch.hpp"
#include "segy_fixtures.hpp"
#include "store_volumes.hpp"

namespace geotandem {
namespace {

using testing::run_geotandem;
using testing::ScratchDir;
using testing::volumes_in;

// Extracts `segy` and `raw` (each a quoted path's inside, then its options) with one worker process
// and expects the same keys with the same volumes. One worker takes the manager's hint (the trace
// index) as two would, and its merge order is fixed, so the runs compare to rounding. With two
// workers the merge order varies from run to run and so do the simplified surfaces within E0: on
// this noisy int16 field (a tangle of thin pockets) one key's volume was seen to differ by up to
// 16 % between two runs of the same raw cube.
void expect_the_components_of(const ScratchDir& dir, const std::string& segy, const std::string& raw) {
  const std::string iso = " --iso 900.5 --block-size 8 --workers 1 --out '";
  auto extracted = run_geotandem("-q extract '" + segy + iso + dir.file("segy") + "'");
  ASSERT_EQ(extracted.exit_code, 0) << extracted.err;
  auto oracle = run_geotandem("-q extract '" + raw + iso + dir.file("raw") + "'");
  ASSERT_EQ(oracle.exit_code, 0) << oracle.err;
  const auto a = volumes_in(dir.file("raw"));
  const auto b = volumes_in(dir.file("segy"));
  ASSERT_GT(a.size(), 0u);
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [key, volume] : a) {
    ASSERT_TRUE(b.count(key)) << "component " << key;
    EXPECT_NEAR(b.at(key), volume, 0.005 * std::abs(volume)) << "component " << key;
  }
}

volume::testing::SegySpec delivered() {
  volume::testing::SegySpec s;
  s.format = SEGY_SIGNED_SHORT_2_BYTE;
  s.little_endian = true;
  s.inline_byte = 9;
  s.crossline_byte = 21;
  return s;
}

TEST(SegyCli, InfoSuggestsTheHeaderBytesThenShowsThemWithTheEncoding) {
  ScratchDir dir;
  const std::string cube = dir.file("f3.sgy");
  volume::testing::write_with_segyio(cube, delivered());

  auto refused = run_geotandem("-q info '" + cube + "'");
  EXPECT_EQ(refused.exit_code, 4) << refused.err; // a format error, not an internal one
  EXPECT_NE(refused.err.find("f3.sgy"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--inline-byte 9 --crossline-byte 21"), std::string::npos) << refused.err;

  auto r = run_geotandem("-q info --json --inline-byte 9 --crossline-byte 21 '" + cube + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["format"], "SEG-Y");
  EXPECT_EQ(j["shape"]["inline"], 7);
  EXPECT_EQ(j["shape"]["crossline"], 9);
  EXPECT_EQ(j["inline"]["first"], 100);
  EXPECT_EQ(j["details"]["sample_format"], "16-bit integer (code 3)");
  EXPECT_EQ(j["details"]["byte_order"], "little-endian");
  EXPECT_EQ(j["details"]["inline_byte"], "9");
  EXPECT_EQ(j["details"]["crossline_byte"], "21");
  EXPECT_EQ(j["values"]["min"].get<double>(), -32768.0); // sample (0, 0, 0) holds the int16 minimum

  auto text = run_geotandem("-q info --no-stats --inline-byte 9 --crossline-byte 21 '" + cube + "'");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("sample format:  16-bit integer (code 3)"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("byte order:     little-endian"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("inline byte:    9"), std::string::npos) << text.out;
}

TEST(SegyCli, ExtractTakesTheHeaderBytes) {
  ScratchDir dir;
  const std::string cube = dir.file("f3.sgy");
  volume::testing::write_with_segyio(cube, delivered());
  auto refused = run_geotandem("-q extract '" + cube + "' --iso 20000 --out '" + dir.file("a") + "'");
  EXPECT_EQ(refused.exit_code, 4) << refused.err;
  EXPECT_NE(refused.err.find("--inline-byte 9"), std::string::npos) << refused.err;
  auto r = run_geotandem("-q extract '" + cube + "' --iso 20000 --inline-byte 9 --crossline-byte 21 --out '" +
                         dir.file("b") + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  // Any byte whose field ends within the 240-byte header is a position; 238 (4 bytes) is not.
  auto bad = run_geotandem("-q extract '" + cube + "' --iso 20000 --inline-byte 238 --out '" + dir.file("c") + "'");
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("238"), std::string::npos) << bad.err;
}

// Header bytes that read the same file as another cube (here the line numbers swapped on a square
// survey without coordinates: the same geometry, the samples transposed) make another extraction:
// the store refuses to resume with them instead of mixing the two cubes' bodies.
TEST(SegyCli, OtherHeaderBytesDoNotResumeAStore) {
  ScratchDir dir;
  const std::string cube = dir.file("square.sgy");
  volume::testing::SegySpec s;
  s.ni = s.nj = 12;
  s.ns = 20;
  s.il0 = s.xl0 = 100;
  s.il_step = s.xl_step = 1;
  s.coordinates = false;
  volume::testing::write_with_segyio(cube, s);
  const std::string store = dir.file("store");
  const std::string extract = "-q extract '" + cube + "' --iso 900.5 --block-size 8 --workers 2 --out '" + store + "'";
  auto first = run_geotandem(extract);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  auto swapped = run_geotandem(extract + " --inline-byte 193 --crossline-byte 189");
  EXPECT_EQ(swapped.exit_code, 2) << swapped.err;
  EXPECT_NE(swapped.err.find("segy: (not recorded) in the store, {\"crossline_byte\":189,\"inline_byte\":193} now"),
            std::string::npos)
      << swapped.err;
  auto again = run_geotandem(extract);
  EXPECT_EQ(again.exit_code, 0) << "the same bytes resume\n" << again.err;
  auto fresh = run_geotandem(extract + " --inline-byte 193 --crossline-byte 189 --fresh");
  ASSERT_EQ(fresh.exit_code, 0) << fresh.err;
  auto runs = run_geotandem("store runs --json '" + store + "'");
  ASSERT_EQ(runs.exit_code, 0) << runs.err;
  const auto last = nlohmann::json::parse(runs.out).back();
  EXPECT_EQ(last["parameters"]["identity"]["segy"]["inline_byte"], 193) << runs.out;
}

// An irregular survey (a corner cut off and a hole inside the body) as delivered: refused by
// default, naming the missing traces; with --nan fill, in local workers, its bodies are those of
// the same samples with NaN where the traces are missing, written as a raw cube (another reader).
TEST(SegyCli, AnIrregularSurveyIsExtractedWithItsMissingTracesOutside) {
  ScratchDir dir;
  volume::testing::SegySpec s = delivered();
  s.format = SEGY_IEEE_FLOAT_4_BYTE; // samples 100 i + j + k / 64 - 300: inside from inline index 12 on
  s.ni = 16;
  s.nj = 12;
  s.ns = 30;
  auto missing = [](int i, int j) { return i + j < 4 || (i >= 12 && i <= 14 && j >= 4 && j <= 6); };
  for (int i = 0; i < s.ni; ++i)
    for (int j = 0; j < s.nj; ++j)
      if (missing(i, j)) s.missing.push_back({i, j});
  const auto present = std::to_string(s.ni * s.nj - static_cast<int>(s.missing.size()));
  const std::string cube = dir.file("outline.sgy");
  volume::testing::write_with_segyio(cube, s);
  const std::string bytes = " --inline-byte 9 --crossline-byte 21";

  auto refused = run_geotandem("-q extract '" + cube + "' --iso 900.5" + bytes + " --out '" + dir.file("a") + "'");
  EXPECT_EQ(refused.exit_code, 4) << refused.err;
  EXPECT_NE(refused.err.find(present + " of 192 traces (16 inlines x 12 crosslines)"), std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("--nan fill"), std::string::npos) << refused.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("a")));

  auto info = run_geotandem("-q info --json" + bytes + " '" + cube + "'");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["values"]["non_finite"], s.missing.size() * 30) << "the missing traces are missing samples";
  EXPECT_NE(j["details"]["traces"].get<std::string>().find("irregular"), std::string::npos) << info.out;

  // The oracle: the samples segyio was given, NaN in the missing bins, on the geometry info reports.
  const auto opened = volume::open_volume(cube, {.nan_policy = volume::NanPolicy::fill, .segy = {9, 21}});
  const volume::Geometry g = opened->geometry();
  std::vector<float> samples;
  for (int i = 0; i < s.ni; ++i)
    for (int jj = 0; jj < s.nj; ++jj)
      for (int k = 0; k < s.ns; ++k)
        samples.push_back(missing(i, jj) ? std::numeric_limits<float>::quiet_NaN()
                                         : volume::testing::expected_sample(s.format, i, jj, k));
  const std::string raw = dir.file("oracle.raw");
  volume::write_volume(volume::MemoryVolume(g, samples), raw);

  expect_the_components_of(dir, cube + "'" + bytes + " --nan fill", raw + "' --nan fill");
}

// A shuffled file (issue 54): `info` says it is read through a trace index and where the fields
// are; an extraction with a worker process (which takes the manager's index) gives the components of the
// same samples written as a raw cube; a duplicated trace is a data error (exit 5) naming both
// traces, never an internal one.
TEST(SegyCli, AnUnsortedFileIsExtractedThroughItsIndex) {
  ScratchDir dir;
  volume::testing::SegySpec s = delivered();
  s.ni = 16;
  s.shuffle = true;
  const std::string cube = dir.file("shuffled.sgy");
  volume::testing::write_with_segyio(cube, s);
  const std::string bytes = " --inline-byte 9 --crossline-byte 21 --coordinate-scalar -10";

  auto info = run_geotandem("-q info --json --no-stats" + bytes + " '" + cube + "'");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto j = nlohmann::json::parse(info.out);
  const auto bins = j["shape"]["inline"].get<int>() * j["shape"]["crossline"].get<int>();
  EXPECT_EQ(bins, s.ni * s.nj);
  EXPECT_EQ(j["details"]["sorting"].get<std::string>().rfind(
                "unsorted: read through a trace index of " + std::to_string(bins) + " bins", 0),
            0u)
      << info.out;
  EXPECT_EQ(j["details"]["inline_type"], "int32");
  EXPECT_NE(j["details"]["coordinate_fields"].get<std::string>().find("scalar -10 given for every trace"),
            std::string::npos)
      << info.out;
  EXPECT_NE(j["details"]["revision"].get<std::string>().find("(binary header bytes 3501-3502)"), std::string::npos);
  auto text = run_geotandem("-q info --no-stats" + bytes + " '" + cube + "'");
  EXPECT_NE(text.out.find("sorting:        unsorted"), std::string::npos) << text.out;

  volume::OpenOptions same; // the geometry the SEG-Y run sees: its coordinates divided by 10
  same.segy = {9, 21};
  same.segy.coordinate_scalar = -10;
  const auto opened = volume::open_volume(cube, same);
  std::vector<float> samples;
  for (int i = 0; i < s.ni; ++i)
    for (int jj = 0; jj < s.nj; ++jj)
      for (int k = 0; k < s.ns; ++k)
        samples.push_back(volume::testing::expected_sample(s.format, i, jj, k));
  const std::string raw = dir.file("oracle.raw");
  ASSERT_EQ(opened->read(opened->geometry().bounds()), samples) << "read in this process through the index";
  volume::write_volume(volume::MemoryVolume(opened->geometry(), samples), raw);
  expect_the_components_of(dir, cube + "'" + bytes, raw + "'");

  // A duplicated trace: the shuffled file with trace 7's header copied onto trace 30's.
  {
    std::fstream f(cube, std::ios::in | std::ios::out | std::ios::binary);
    const long trace_bytes = 240 + 2L * s.ns;
    std::vector<char> header(240);
    f.seekg(s.trace0() + 7 * trace_bytes);
    f.read(header.data(), 240);
    f.seekp(s.trace0() + 30 * trace_bytes);
    f.write(header.data(), 240);
  }
  auto duplicated = run_geotandem("-q info --no-stats" + bytes + " '" + cube + "'");
  EXPECT_EQ(duplicated.exit_code, 5) << duplicated.err;
  EXPECT_NE(duplicated.err.find("traces 7 and 30 both hold inline"), std::string::npos) << duplicated.err;
  EXPECT_NE(duplicated.err.find("shuffled.sgy"), std::string::npos) << duplicated.err;
}

} // namespace
} // namespace geotandem
