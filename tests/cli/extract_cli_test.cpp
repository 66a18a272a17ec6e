// `geotandem extract` as a real child process: one block and the in-process block tree give the
// same components; bad requests exit with their reason and leave no store behind.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <vector>

#include <nlohmann/json.hpp>

#include "gdal_fixtures.hpp"
#include "scratch.hpp"
#include "store_volumes.hpp"

namespace geotandem {
namespace {

using testing::run_geotandem;
using testing::ScratchDir;
using testing::volumes_in;

TEST(ExtractCli, BlocksGiveTheSameComponentsAsOneBlock) {
  ScratchDir dir;
  const std::string cube = dir.file("cube.raw");
  ASSERT_EQ(run_geotandem("-q synth --kind analytic --shape 64 56 48 --seed 3 --out '" + cube + "'").exit_code, 0);
  auto one = run_geotandem("-q extract '" + cube + "' --iso 0.5 --out '" + dir.file("one") + "'");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  auto blocks = run_geotandem("-q extract '" + cube + "' --iso 0.5 --block-size 16 --out '" + dir.file("blocks") + "'");
  ASSERT_EQ(blocks.exit_code, 0) << blocks.err;

  const auto a = volumes_in(dir.file("one"));
  const auto b = volumes_in(dir.file("blocks"));
  ASSERT_GT(a.size(), 3u) << "the analytic cube has several bodies";
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [key, volume] : a) {
    ASSERT_TRUE(b.count(key)) << "component " << key << " missing from the block run";
    EXPECT_NEAR(b.at(key), volume, 0.005 * std::abs(volume) + 1e-9) << "component " << key;
  }
  // The run is recorded in the store with its statistics.
  auto runs = run_geotandem("store runs --json '" + dir.file("blocks") + "'");
  ASSERT_EQ(runs.exit_code, 0) << runs.err;
  EXPECT_NE(runs.out.find("block"), std::string::npos) << runs.out;
}

TEST(ExtractCli, BadRequestsExitWithTheirReason) {
  ScratchDir dir;
  const std::string cube = dir.file("cube.raw");
  ASSERT_EQ(run_geotandem("-q synth --kind analytic --shape 40 40 40 --out '" + cube + "'").exit_code, 0);
  struct Bad {
    std::string args;
    int code;
    std::string mention;
  };
  const std::vector<Bad> cases = {
      {"extract '" + cube + "' --iso 0.5 --block-size 4 --out '" + dir.file("s1") + "'", 2, "block-size"},
      {"extract '" + dir.file("missing.sgy") + "' --iso 0.5 --out '" + dir.file("s2") + "'", 3, "missing.sgy"},
      {"extract '" + cube + "' --iso 0.5 --mode fast --out '" + dir.file("s3") + "'", 2, "fast"},
      {"extract '" + cube + "' --iso 0.5 --isotropy 2 --out '" + dir.file("s4") + "'", 2, "2"},
      {"extract '" + cube + "' --out '" + dir.file("s5") + "'", 2, "--iso"},
  };
  for (const auto& c : cases) {
    auto r = run_geotandem(c.args);
    EXPECT_EQ(r.exit_code, c.code) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.mention), std::string::npos) << c.args << ": '" << c.mention << "' missing from\n" << r.err;
  }
  for (const char* store : {"s1", "s2", "s3", "s5"})
    EXPECT_FALSE(std::filesystem::exists(dir.file(store))) << store << ": a refused request left a store behind";
}

// Rewrites the first `inlines` inlines of a raw float32 cube of `per_inline` samples each to `value`.
void overwrite_inlines(const std::string& raw, std::size_t inlines, std::size_t per_inline, float value) {
  std::fstream f(raw, std::ios::in | std::ios::out | std::ios::binary);
  ASSERT_TRUE(f.good()) << raw;
  const std::vector<float> nulls(inlines * per_inline, value);
  f.write(reinterpret_cast<const char*>(nulls.data()), static_cast<std::streamsize>(nulls.size() * sizeof(float)));
  ASSERT_TRUE(f.good()) << raw;
}

// --no-data names a raw or SEG-Y cube's null: such samples are missing, an error by default, outside
// with --nan fill, in local workers as in this process; the store records it, so a run that reads
// them as values does not resume it.
TEST(ExtractCli, NoDataNamesTheMissingSamplesOfACubeThatCannotDeclareThem) {
  ScratchDir dir;
  const std::string nulls = dir.file("nulls.raw"), holes = dir.file("holes.raw");
  for (const std::string& cube : {nulls, holes}) {
    ASSERT_EQ(run_geotandem("-q synth --kind analytic --shape 48 44 40 --seed 3 --out '" + cube + "'").exit_code, 0);
    overwrite_inlines(cube, 6, 44 * 40, cube == nulls ? -999.25f : std::numeric_limits<float>::quiet_NaN());
  }
  auto strict = run_geotandem("-q extract '" + nulls + "' --iso 0.5 --no-data -999.25 --out '" + dir.file("s0") + "'");
  EXPECT_EQ(strict.exit_code, 5) << strict.err;
  EXPECT_NE(strict.err.find("no-data sample at index (0, 0, 0) (-999.25, the no-data value given)"), std::string::npos)
      << strict.err;

  auto given = run_geotandem("-q extract '" + nulls + "' --iso 0.5 --no-data -999.25 --nan fill --workers 2 " +
                             "--block-size 16 --out '" + dir.file("given") + "'");
  ASSERT_EQ(given.exit_code, 0) << given.err;
  auto nan =
      run_geotandem("-q extract '" + holes + "' --iso 0.5 --nan fill --workers 0 --out '" + dir.file("nan") + "'");
  ASSERT_EQ(nan.exit_code, 0) << nan.err;
  const auto a = volumes_in(dir.file("nan"));
  const auto b = volumes_in(dir.file("given"));
  ASSERT_GT(a.size(), 3u);
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [key, volume] : a) {
    ASSERT_TRUE(b.count(key)) << "component " << key << " missing when the nulls are named";
    EXPECT_NEAR(b.at(key), volume, 0.005 * std::abs(volume) + 1e-9) << "component " << key;
  }

  auto values = run_geotandem("-q extract '" + nulls + "' --iso 0.5 --nan fill --workers 2 --block-size 16 --out '" +
                              dir.file("given") + "'");
  EXPECT_EQ(values.exit_code, 2) << values.err;
  EXPECT_NE(values.err.find("no_data: -999.25 in the store"), std::string::npos) << values.err;
  auto range = run_geotandem("-q extract '" + nulls + "' --iso 0.5 --no-data 1e39 --out '" + dir.file("s1") + "'");
  EXPECT_EQ(range.exit_code, 2) << range.err;
  EXPECT_NE(range.err.find("--no-data is 1e+39"), std::string::npos) << range.err;
}

// -q leaves warnings, errors and the summary: no info lines from the manager nor from the local
// workers it starts (they get its log level). An explicit --log-level still applies.
TEST(ExtractCli, QuietLeavesNoInfoLinesFromTheManagerOrItsWorkers) {
  ScratchDir dir;
  const std::string cube = dir.file("cube.raw");
  ASSERT_EQ(run_geotandem("-q synth --kind analytic --shape 40 40 40 --seed 2 --out '" + cube + "'").exit_code, 0);
  const std::string extract = "extract '" + cube + "' --iso 0.5 --block-size 16 --workers 2 --out ";
  auto plain = run_geotandem(extract + "'" + dir.file("plain") + "'");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_NE(plain.err.find("info: worker"), std::string::npos) << "without -q the workers say they joined\n"
                                                               << plain.err;
  auto quiet = run_geotandem("-q " + extract + "'" + dir.file("quiet") + "'");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err.find("info:"), std::string::npos) << quiet.err;
  EXPECT_EQ(volumes_in(dir.file("quiet")).size(), volumes_in(dir.file("plain")).size());
  auto asked = run_geotandem("-q --log-level info " + extract + "'" + dir.file("asked") + "'");
  ASSERT_EQ(asked.exit_code, 0) << asked.err;
  EXPECT_NE(asked.err.find("info:"), std::string::npos) << asked.err;
}

// A netCDF file that holds two cubes, written through GDAL as another tool would: `ball` has one
// body, `balls` two, on the same grid.
void write_two_cubes(const std::string& path) {
  using gdal_fixtures::add_array;
  gdal_fixtures::write_foreign(path, "netCDF", [](GDALGroup& root) {
    const int n = 32;
    const std::array dims{root.CreateDimension("iline", "", "", n), root.CreateDimension("xline", "", "", n),
                          root.CreateDimension("twt", "", "", n)};
    const std::vector<std::shared_ptr<GDALDimension>> cube(dims.begin(), dims.end());
    for (const char* name : {"ball", "balls"}) {
      std::vector<float> values;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          for (int k = 0; k < n; ++k) {
            auto ball = [&](double c, double r) { return r - std::hypot(i - c, j - c, k - c); };
            values.push_back(
                static_cast<float>(name == std::string("ball") ? ball(16, 7) : std::max(ball(8, 5), ball(23, 5))));
          }
      const GUInt64 start[3] = {0, 0, 0};
      const std::size_t count[3] = {n, n, n};
      ASSERT_TRUE(
          add_array(root, name, cube, GDT_Float32)
              ->Write(start, count, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float32), values.data()));
    }
  });
}

// Another array of the same file is another extraction: `info` and `extract` take --variable, and
// a store made from one array refuses to resume with the other (it resumed, reporting the first
// array's bodies as the second's, with workers; it mixed both without).
TEST(ExtractCli, AnotherArrayOfTheFileIsAnotherExtraction) {
  ScratchDir dir;
  const std::string cube = dir.file("two.nc");
  write_two_cubes(cube);
  auto several = run_geotandem("-q info '" + cube + "'");
  EXPECT_NE(several.exit_code, 0);
  EXPECT_NE(several.err.find("--variable"), std::string::npos) << several.err;
  auto info = run_geotandem("-q info --json --no-stats --variable balls '" + cube + "'");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_EQ(nlohmann::json::parse(info.out)["details"]["array"], "/balls") << info.out;

  const std::string store = dir.file("store");
  const std::string extract = "-q extract '" + cube + "' --iso 0 --block-size 8 --out '" + store + "'";
  auto one = run_geotandem(extract + " --variable ball --workers 2");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_EQ(volumes_in(store).size(), 1u);
  for (const char* workers : {"2", "0"}) {
    auto other = run_geotandem(extract + " --variable balls --workers " + workers);
    EXPECT_EQ(other.exit_code, 2) << other.err;
    EXPECT_NE(other.err.find("variable: /ball in the store, /balls now"), std::string::npos) << other.err;
    EXPECT_EQ(volumes_in(store).size(), 1u) << "nothing of the other array went in";
  }
  auto resumed = run_geotandem(extract + " --variable /ball --workers 2");
  EXPECT_EQ(resumed.exit_code, 0) << "the same array, by its full name, resumes\n" << resumed.err;
  auto fresh = run_geotandem(extract + " --variable balls --workers 2 --fresh");
  ASSERT_EQ(fresh.exit_code, 0) << fresh.err;
  EXPECT_EQ(volumes_in(store).size(), 2u);
}

} // namespace
} // namespace geotandem
