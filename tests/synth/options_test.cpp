// Parameter validation, the ground-truth JSON and names.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "geotandem/core/error.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "scratch.hpp"

namespace geotandem::synth {
namespace {

// Runs `f`, expects InvalidArgument, and returns its message.
template <class F> std::string invalid(F&& f) {
  try {
    f();
  } catch (const InvalidArgument& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InvalidArgument, got: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected InvalidArgument, nothing was thrown";
  return {};
}

void expect_mentions(const std::string& message, std::initializer_list<const char*> parts) {
  for (const char* part : parts)
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' missing from: " << message;
}

TEST(SynthOptions, ShapesBelowTheMinimumAreRefused) {
  AnalyticOptions a;
  a.shape = {64, 39, 64};
  expect_mentions(invalid([&] { make_analytic(a); }), {"shape", "39", "crossline", "40"});
  SeismicOptions s;
  s.shape = {64, 64, 8};
  expect_mentions(invalid([&] { make_seismic(s); }), {"shape", "8", "sample", "40"});
  s.shape = {-5, 64, 64};
  expect_mentions(invalid([&] { make_seismic(s); }), {"-5", "inline"});
  a.shape = {40, 40, 40}; // the minimum is accepted
  EXPECT_NO_THROW(make_analytic(a));
}

TEST(SynthOptions, SeismicParametersAreChecked) {
  SeismicOptions s;
  s.shape = {48, 48, 48};
  s.snr = 0.0;
  expect_mentions(invalid([&] { make_seismic(s); }), {"snr", "0", "(0, inf]"});
  s.snr = -2.0;
  expect_mentions(invalid([&] { make_seismic(s); }), {"snr", "-2"});
  s.snr = std::nan("");
  expect_mentions(invalid([&] { make_seismic(s); }), {"snr", "nan"});
  s.snr = 4.0;
  s.peak_frequency_hz = 125.0; // Nyquist at 4 ms
  expect_mentions(invalid([&] { make_seismic(s); }), {"peak_frequency_hz", "125", "(0, 125)", "Nyquist"});
  s.peak_frequency_hz = 0.0;
  expect_mentions(invalid([&] { make_seismic(s); }), {"peak_frequency_hz", "0"});
  s.survey.dz = 2.0; // Nyquist 250 Hz: 125 Hz is fine now
  s.peak_frequency_hz = 125.0;
  EXPECT_NO_THROW(make_seismic(s));
  s.survey.dz = 4.0;
  s.peak_frequency_hz = 30.0;
  s.chaotic_gain = 0.5;
  expect_mentions(invalid([&] { make_seismic(s); }), {"chaotic_gain", "0.5", "[1, 10]"});
  s.chaotic_gain = 2.5;
  s.reflector_spacing = 0.2;
  expect_mentions(invalid([&] { make_seismic(s); }), {"reflector_spacing", "0.2"});
  s.reflector_spacing = 3.0;
  s.survey.z_unit = volume::SampleUnit::metres;
  expect_mentions(invalid([&] { make_seismic(s); }), {"z_unit", "ms"});
  s.snr = std::numeric_limits<double>::infinity(); // no noise is allowed
  s.survey.z_unit = volume::SampleUnit::milliseconds;
  EXPECT_NO_THROW(make_seismic(s));
}

TEST(SynthOptions, SurveyAndDensitiesAreChecked) {
  AnalyticOptions a;
  a.shape = {40, 40, 40};
  a.survey.bin_inline_m = -25.0;
  expect_mentions(invalid([&] { make_analytic(a); }), {"bin_inline_m", "-25", "m"});
  a.survey.bin_inline_m = 5.0;
  expect_mentions(invalid([&] { make_analytic(a); }), {"aspect ratio", "0.2", "[0.25, 4]"});
  a.survey.bin_inline_m = 25.0;
  a.survey.dz = 0.0;
  expect_mentions(invalid([&] { make_analytic(a); }), {"dz", "0"});
  a.survey.dz = 4.0;
  a.survey.rotation_deg = std::numeric_limits<double>::infinity();
  expect_mentions(invalid([&] { make_analytic(a); }), {"rotation_deg", "inf"});
  a.survey.rotation_deg = 30.0;
  a.bubble_density = 5000.0;
  expect_mentions(invalid([&] { make_analytic(a); }), {"bubble_density", "5000", "[0, 2000]"});
  a.bubble_density = 100.0;
  a.body_density = -1.0;
  expect_mentions(invalid([&] { make_analytic(a); }), {"body_density", "-1"});
  expect_mentions(invalid([] { parse_cube_kind("fractal"); }), {"fractal", "analytic", "seismic"});
}

TEST(SynthTruth, JsonHoldsWhatWasPlanted) {
  AnalyticOptions a;
  a.shape = {64, 56, 48};
  a.seed = 3;
  auto cube = make_analytic(a);
  const auto j = to_json(cube->truth());
  EXPECT_EQ(j["kind"], "analytic");
  EXPECT_EQ(j["seed"], 3);
  EXPECT_EQ(j["geometry"]["shape"], nlohmann::json({64, 56, 48}));
  EXPECT_EQ(j["iso"], 0.5);
  EXPECT_EQ(j["world_volume_unit"], "m2*ms");
  EXPECT_EQ(j["bubbles"]["count"], cube->truth().bubble_count);
  EXPECT_EQ(j["block_planes"]["inline"], nlohmann::json({16, 32, 48}));
  ASSERT_EQ(j["bodies"].size(), cube->truth().bodies.size());
  int cavities = 0;
  for (const auto& b : j["bodies"]) {
    for (const char* key : {"name", "type", "centre_index", "centre_world", "azimuth_deg", "volume_voxels",
                            "volume_world", "bounds_index", "dimensions", "crosses_block_plane", "cut_by_border",
                            "has_cavity", "chaotic", "negative_control"})
      EXPECT_TRUE(b.contains(key)) << key;
    EXPECT_GE(b["azimuth_deg"].get<double>(), 0.0);
    EXPECT_LT(b["azimuth_deg"].get<double>(), 180.0);
    EXPECT_NEAR(b["volume_world"].get<double>(), b["volume_voxels"].get<double>() * 25.0 * 25.0 * 4.0,
                1e-6 * b["volume_world"].get<double>());
    cavities += b["has_cavity"].get<bool>();
  }
  EXPECT_EQ(cavities, 1);

  SeismicOptions s;
  s.shape = {48, 48, 48};
  s.snr = std::numeric_limits<double>::infinity();
  const auto sj = to_json(make_seismic(s)->truth());
  EXPECT_TRUE(sj["seismic"]["snr"].is_null()); // JSON has no infinity
  EXPECT_TRUE(sj["iso"].is_null());
  EXPECT_EQ(sj["seismic"]["noise_rms"], 0.0);
  int controls = 0;
  for (const auto& b : sj["bodies"])
    controls += b["negative_control"].get<bool>() && !b["chaotic"].get<bool>() && !b["volume_exact"].get<bool>();
  EXPECT_EQ(controls, 1);
}

TEST(SynthTruth, WrittenFileReadsBack) {
  testing::ScratchDir dir;
  AnalyticOptions a;
  a.shape = {40, 40, 40};
  auto cube = make_analytic(a);
  const std::string path = truth_path_for(dir.file("cube.nc"));
  EXPECT_EQ(path, dir.file("cube.nc.truth.json"));
  write_ground_truth(cube->truth(), path);
  std::ifstream in(path);
  EXPECT_EQ(nlohmann::json::parse(in), to_json(cube->truth()));

  // Written body by body, it is still the text of the whole document: with bodies, with keys after
  // them (a seismic cube's "seismic"), and with none.
  SeismicOptions s;
  s.shape = {48, 48, 40};
  GroundTruth empty = cube->truth();
  empty.bodies.clear();
  int written = 0;
  for (const GroundTruth& truth : {cube->truth(), make_seismic(s)->truth(), empty}) {
    SCOPED_TRACE("cube " + std::to_string(written));
    const std::string file = dir.file("truth" + std::to_string(written++) + ".json");
    write_ground_truth(truth, file);
    std::ifstream text_in(file);
    const std::string text((std::istreambuf_iterator<char>(text_in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text, to_json(truth).dump(2) + "\n");
  }
  EXPECT_GT(cube->truth().bodies.size(), 1u);
  EXPECT_THROW(write_ground_truth(cube->truth(), dir.file("missing/dir/cube.truth.json")), IoError);
  EXPECT_EQ(truth_path_for("out/cube.zarr/"), "out/cube.zarr.truth.json");
}

TEST(SynthTruth, CubesNameThemselves) {
  AnalyticOptions a;
  a.shape = {40, 41, 42};
  a.seed = 9;
  auto cube = make_analytic(a);
  EXPECT_EQ(cube->format(), "synthetic analytic");
  EXPECT_EQ(cube->source(), "synthetic analytic cube (seed 9, 40x41x42)");
  EXPECT_EQ(cube->geometry().shape, (volume::Index3{40, 41, 42}));
  EXPECT_NO_THROW(cube->geometry().validate());
  // Reads outside the cube are refused by Volume::read.
  EXPECT_THROW(cube->read(volume::Box{{0, 0, 0}, {41, 1, 1}}), InvalidArgument);
}

} // namespace
} // namespace geotandem::synth
