// `geotandem info` on cubes written by `geotandem synth`, as a real child process.

#include <gtest/gtest.h>

#include <fstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "scratch.hpp"

namespace geotandem {
namespace {

using testing::run_geotandem;
using testing::ScratchDir;

TEST(InfoCli, ReportsShapeGeometryAndValues) {
  ScratchDir dir;
  for (const std::string name : {"a.raw", "a.nc"}) {
    const std::string cube = dir.file(name);
    ASSERT_EQ(run_geotandem("-q synth --kind analytic --shape 44 40 48 --out '" + cube + "'").exit_code, 0);
    auto r = run_geotandem("-q info --json '" + cube + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["shape"]["inline"], 44);
    EXPECT_EQ(j["shape"]["crossline"], 40);
    EXPECT_EQ(j["shape"]["sample"], 48);
    EXPECT_EQ(j["samples"], 44 * 40 * 48);
    EXPECT_EQ(j["sample"]["interval"], 4.0);
    EXPECT_EQ(j["sample"]["unit"], "ms");
    EXPECT_NEAR(j["bin_size_m"][0].get<double>(), 25.0, 1e-9);
    EXPECT_NEAR(j["bin_size_m"][1].get<double>(), 25.0, 1e-9);
    EXPECT_EQ(j["format"], name.ends_with(".nc") ? "netCDF-4" : "raw");
    // The analytic field lies in [0, 1] and reaches 1 inside bodies.
    EXPECT_GE(j["values"]["min"].get<double>(), 0.0);
    EXPECT_EQ(j["values"]["max"].get<double>(), 1.0);
    EXPECT_EQ(j["values"]["non_finite"], 0);

    auto text = run_geotandem("-q info '" + cube + "'");
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.out.find("44 inlines x 40 crosslines x 48 samples"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("format:     " + std::string(name.ends_with(".nc") ? "netCDF-4" : "raw")),
              std::string::npos)
        << text.out;
  }
}

TEST(InfoCli, NoStatsSkipsTheValueScan) {
  ScratchDir dir;
  const std::string cube = dir.file("s.raw");
  ASSERT_EQ(run_geotandem("-q synth --kind seismic --shape 40 40 40 --out '" + cube + "'").exit_code, 0);
  auto r = run_geotandem("-q info --json --no-stats '" + cube + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(nlohmann::json::parse(r.out).contains("values"));
}

// A null value a raw or SEG-Y cube cannot declare (here -999.25 in the first 5 inlines of a seismic
// cube) is pointed out, with the option that makes it missing; with that option it is counted as
// missing. Amplitudes that merely saturate (the analytic cube's bodies hold 1 at their cores) are not.
TEST(InfoCli, ANullValueFarOutsideTheAmplitudesIsPointedOut) {
  ScratchDir dir;
  const std::string cube = dir.file("nulls.raw"), analytic = dir.file("analytic.raw");
  ASSERT_EQ(run_geotandem("-q synth --kind seismic --shape 40 42 44 --out '" + cube + "'").exit_code, 0);
  {
    std::fstream f(cube, std::ios::in | std::ios::out | std::ios::binary);
    const std::vector<float> nulls(5 * 42 * 44, -999.25f);
    f.write(reinterpret_cast<const char*>(nulls.data()), static_cast<std::streamsize>(nulls.size() * sizeof(float)));
    ASSERT_TRUE(f.good());
  }
  auto text = run_geotandem("-q info '" + cube + "'");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("9240 samples (12.5 %) hold -999.25"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("pass --no-data -999.25"), std::string::npos) << text.out;
  auto json = run_geotandem("-q info --json '" + cube + "'");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const auto nulls = nlohmann::json::parse(json.out)["values"]["suspected_nulls"];
  ASSERT_EQ(nulls.size(), 1u) << json.out;
  EXPECT_EQ(nulls[0]["value"], -999.25);
  EXPECT_EQ(nulls[0]["samples"], 9240);

  auto named = run_geotandem("-q info --json --no-data -999.25 '" + cube + "'");
  ASSERT_EQ(named.exit_code, 0) << named.err;
  const auto values = nlohmann::json::parse(named.out)["values"];
  EXPECT_EQ(values["non_finite"], 9240);
  EXPECT_TRUE(values["suspected_nulls"].empty()) << named.out;
  EXPECT_GT(values["min"].get<double>(), -100.0);

  ASSERT_EQ(run_geotandem("-q synth --kind analytic --shape 44 40 48 --out '" + analytic + "'").exit_code, 0);
  auto saturated = run_geotandem("-q info --json '" + analytic + "'");
  ASSERT_EQ(saturated.exit_code, 0) << saturated.err;
  const auto v = nlohmann::json::parse(saturated.out)["values"];
  EXPECT_GT(v["at_max"].get<std::uint64_t>(), 1u) << "the analytic bodies' cores hold 1";
  EXPECT_TRUE(v["suspected_nulls"].empty()) << saturated.out;
}

TEST(InfoCli, MissingFileIsAnIoError) {
  ScratchDir dir;
  auto r = run_geotandem("info '" + dir.file("nothing.nc") + "'");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("nothing.nc"), std::string::npos) << r.err;
}

} // namespace
} // namespace geotandem
