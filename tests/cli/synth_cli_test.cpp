// `geotandem synth` as a real child process: it writes the cube and its ground truth, the cube is
// the one the library computes, and bad arguments fail with the documented exit codes.

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "geotandem/synth/synthetic.hpp"
#include "geotandem/volume/io.hpp"
#include "scratch.hpp"

namespace geotandem {
namespace {

using testing::run_geotandem;
using testing::ScratchDir;

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST(SynthCli, AnalyticRawCubeAndTruthAreWritten) {
  ScratchDir dir;
  const std::string cube = dir.file("a.raw");
  auto r = run_geotandem("synth --kind analytic --shape 48 40 44 --seed 5 --out '" + cube + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string truth_path = cube + ".truth.json";
  EXPECT_NE(r.out.find(truth_path), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("48 x 40 x 44"), std::string::npos) << r.out;
  ASSERT_TRUE(std::filesystem::exists(truth_path));

  synth::AnalyticOptions options;
  options.shape = {48, 40, 44};
  options.seed = 5;
  auto expected = synth::make_analytic(options);
  const auto truth = read_json(truth_path);
  EXPECT_EQ(truth, synth::to_json(expected->truth()));
  EXPECT_NE(r.out.find(std::to_string(expected->truth().bodies.size()) + " planted bodies"), std::string::npos);

  auto written = volume::open_volume(cube);
  EXPECT_EQ(written->geometry().shape, (volume::Index3{48, 40, 44}));
  EXPECT_EQ(written->geometry().affine, expected->geometry().affine);
  EXPECT_TRUE(same_bits(written->read(written->geometry().bounds()), expected->read(expected->geometry().bounds())));
}

TEST(SynthCli, SeismicNetcdfCubeMatchesTheLibrary) {
  ScratchDir dir;
  const std::string cube = dir.file("s.nc");
  auto r =
      run_geotandem("-q synth --kind seismic --shape 40 44 48 --seed 2 --snr 2 --frequency 25 --out '" + cube + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, ""); // -q: no progress
  EXPECT_NE(r.out.find("25 Hz"), std::string::npos) << r.out;
  const auto truth = read_json(cube + ".truth.json");
  EXPECT_EQ(truth["kind"], "seismic");
  EXPECT_EQ(truth["seismic"]["snr"], 2.0);
  EXPECT_EQ(truth["seismic"]["peak_frequency_hz"], 25.0);

  synth::SeismicOptions options;
  options.shape = {40, 44, 48};
  options.seed = 2;
  options.snr = 2.0;
  options.peak_frequency_hz = 25.0;
  auto expected = synth::make_seismic(options);
  auto written = volume::open_volume(cube);
  EXPECT_EQ(written->geometry().shape, (volume::Index3{40, 44, 48}));
  EXPECT_TRUE(same_bits(written->read(written->geometry().bounds()), expected->read(expected->geometry().bounds())));
}

TEST(SynthCli, ExistingOutputNeedsOverwrite) {
  ScratchDir dir;
  const std::string cube = dir.file("c.raw");
  const std::string args = "-q synth --shape 40 40 40 --out '" + cube + "'";
  ASSERT_EQ(run_geotandem(args).exit_code, 0);
  auto again = run_geotandem(args);
  EXPECT_EQ(again.exit_code, 3) << again.err; // IoError
  EXPECT_NE(again.err.find("--overwrite"), std::string::npos) << again.err;
  auto forced = run_geotandem(args + " --overwrite --seed 9");
  EXPECT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_EQ(read_json(cube + ".truth.json")["seed"], 9);
}

TEST(SynthCli, BadArgumentsFailWithTheirReason) {
  ScratchDir dir;
  const std::string out = " --out '" + dir.file("x.raw") + "'";
  struct Bad {
    std::string args;
    int code; // -1: a usage error found by the argument parser (exit code 2 as well)
    std::vector<std::string> mentions;
  };
  const std::vector<Bad> cases = {
      {"synth --shape 20 64 64" + out, 2, {"20", "inline", "40"}},
      {"synth --kind seismic --snr 0 --shape 48 48 48" + out, 2, {"snr", "0"}},
      {"synth --kind seismic --frequency 200 --shape 48 48 48" + out, 2, {"peak_frequency_hz", "200", "Nyquist"}},
      {"synth --kind analytic --snr 3 --shape 48 48 48" + out, 2, {"--snr", "seismic"}},
      {"synth --kind fractal --shape 48 48 48" + out, -1, {"fractal"}},
      {"synth --shape 48 48 48 --out '" + dir.file("x.xyz") + "'", 2, {".xyz", ".nc"}},
      {"synth --shape 48 48" + out, -1, {"shape"}},
  };
  for (const auto& c : cases) {
    auto r = run_geotandem(c.args);
    if (c.code < 0) {
      EXPECT_EQ(r.exit_code, 2) << c.args << ": a usage error\n" << r.err;
    } else {
      EXPECT_EQ(r.exit_code, c.code) << c.args << "\n" << r.err;
    }
    for (const auto& m : c.mentions)
      EXPECT_NE(r.err.find(m), std::string::npos) << c.args << ": '" << m << "' missing from\n" << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.raw")));
}

} // namespace
} // namespace geotandem
