// The seismic kind: what an interpreter's attributes rely on. Chaotic bodies are bright and
// laterally incoherent, the bright spot is bright and coherent, the background is coherent; the
// noise has the announced RMS, the wavelet's spectrum and the lateral smoothing.

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

#include "synth_test_support.hpp"

namespace geotandem::synth {
namespace {

constexpr double no_noise = std::numeric_limits<double>::infinity();

struct Window {
  double rms;       // of the trace at the point
  double coherence; // mean correlation with the four neighbouring traces
};

// Statistics of a vertical window of +-hw samples around (i, j, k).
Window window_at(const std::vector<float>& v, const volume::Box& box, std::int64_t i, std::int64_t j, std::int64_t k,
                 int hw) {
  auto at = [&](std::int64_t a, std::int64_t b, std::int64_t c) {
    return static_cast<double>(v[box.offset({a, b, c})]);
  };
  double energy = 0.0, coherence = 0.0;
  for (auto kk = k - hw; kk <= k + hw; ++kk)
    energy += at(i, j, kk) * at(i, j, kk);
  for (auto [di, dj] : {std::pair{1, 0}, {0, 1}, {-1, 0}, {0, -1}}) {
    double sxy = 0.0, sxx = 0.0, syy = 0.0;
    for (auto kk = k - hw; kk <= k + hw; ++kk) {
      const double x = at(i, j, kk), y = at(i + di, j + dj, kk);
      sxy += x * y;
      sxx += x * x;
      syy += y * y;
    }
    coherence += sxy / std::sqrt(sxx * syy + 1e-300) / 4.0;
  }
  return {std::sqrt(energy / (2 * hw + 1)), coherence};
}

double rms(const std::vector<float>& v) {
  double sum = 0.0;
  for (float x : v)
    sum += static_cast<double>(x) * x;
  return std::sqrt(sum / static_cast<double>(v.size()));
}

TEST(SeismicCube, ChaoticBodiesAreBrightAndIncoherentTheBrightSpotIsCoherent) {
  double chaotic_coherence = 0.0;
  int chaotic = 0, spots = 0;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SeismicOptions options;
    options.shape = {96, 96, 96};
    options.seed = seed;
    options.snr = no_noise;
    auto cube = make_seismic(options);
    const auto& truth = cube->truth();
    const auto box = cube->geometry().bounds();
    const auto v = cube->read(box);

    // Background: a grid of points well away from every body.
    double background_energy = 0.0, background_coherence = 0.0;
    int n = 0;
    for (std::int64_t i = 4; i < 92; i += 7)
      for (std::int64_t j = 4; j < 92; j += 7)
        for (std::int64_t k = 8; k < 88; k += 9) {
          bool near = false;
          for (const auto& b : truth.bodies) {
            const double grow[3] = {6.0, 6.0, 14.0};
            const std::int64_t p[3] = {i, j, k};
            bool in = true;
            for (int a = 0; a < 3; ++a)
              in = in && p[a] > b.bounds_lo[a] - grow[a] && p[a] < b.bounds_hi[a] + grow[a];
            near = near || in;
          }
          if (near) continue;
          const auto w = window_at(v, box, i, j, k, 4);
          background_energy += w.rms * w.rms;
          background_coherence += w.coherence;
          ++n;
        }
    ASSERT_GT(n, 100);
    const double background_rms = std::sqrt(background_energy / n);
    EXPECT_GT(background_coherence / n, 0.95) << "folded layers must be laterally continuous";
    EXPECT_NEAR(background_rms, truth.seismic->background_rms, 0.25 * truth.seismic->background_rms);

    for (const auto& b : truth.bodies) {
      if (b.cut_by_border) continue;
      const auto i = std::lround(b.centre_index[0]), j = std::lround(b.centre_index[1]);
      const auto k = std::lround(b.centre_index[2]);
      double energy = 0.0, coherence = 0.0;
      for (int di = -1; di <= 1; ++di)
        for (int dj = -1; dj <= 1; ++dj) {
          const auto w = window_at(v, box, i + di, j + dj, k, 3);
          energy += w.rms * w.rms / 9.0;
          coherence += w.coherence / 9.0;
        }
      const double ratio = std::sqrt(energy) / background_rms;
      if (b.negative_control) {
        ++spots;
        EXPECT_FALSE(b.chaotic);
        EXPECT_EQ(b.type, BodyType::bright_spot);
        EXPECT_GT(ratio, 1.5) << b.name << " is not bright";
        EXPECT_GT(coherence, 0.95) << b.name << " is not continuous";
      } else {
        ++chaotic;
        EXPECT_TRUE(b.chaotic);
        EXPECT_GT(ratio, 1.3) << b.name << " is not bright";
        EXPECT_LT(coherence, 0.7) << b.name << " is not chaotic";
        chaotic_coherence += coherence;
      }
    }
  }
  EXPECT_EQ(spots, 3);
  EXPECT_GE(chaotic, 9);
  EXPECT_LT(chaotic_coherence / chaotic, 0.35);
}

TEST(SeismicCube, NoiseHasTheAnnouncedRmsAndLateralSmoothing) {
  SeismicOptions options;
  options.shape = {64, 64, 64};
  options.seed = 5;
  options.snr = no_noise;
  auto clean = make_seismic(options);
  options.snr = 2.0;
  auto noisy = make_seismic(options);
  const auto& t = *noisy->truth().seismic;
  EXPECT_DOUBLE_EQ(t.noise_rms * 2.0, t.signal_rms);
  EXPECT_EQ(clean->truth().seismic->noise_rms, 0.0);
  EXPECT_DOUBLE_EQ(clean->truth().seismic->signal_rms, t.signal_rms); // noise does not change the signal

  const auto box = clean->geometry().bounds();
  const auto a = clean->read(box), b = noisy->read(box);
  std::vector<float> noise(a.size());
  for (std::size_t n = 0; n < a.size(); ++n)
    noise[n] = b[n] - a[n];
  // The signal RMS is estimated on 256 traces; the whole cube may differ a little.
  EXPECT_NEAR(rms(a), t.signal_rms, 0.15 * t.signal_rms);
  // 260k noise samples, correlated over about 20 x 3 x 3 of them: the RMS is known to about 2 %.
  EXPECT_NEAR(rms(noise), t.noise_rms, 0.06 * t.noise_rms);
  // The [1 2 1]/4 kernel across traces correlates neighbours by 4/6 along each axis.
  double sxy = 0.0, sxx = 0.0;
  for (std::int64_t i = 0; i + 1 < 64; ++i)
    for (std::int64_t j = 0; j < 64; ++j)
      for (std::int64_t k = 0; k < 64; ++k) {
        const double x = noise[box.offset({i, j, k})], y = noise[box.offset({i + 1, j, k})];
        sxy += x * y;
        sxx += x * x;
      }
  EXPECT_NEAR(sxy / sxx, 4.0 / 6.0, 0.05);
}

// Mean power spectrum of the noise along the traces peaks at the Ricker peak frequency.
double noise_peak_frequency(double peak_hz) {
  SeismicOptions options;
  options.shape = {40, 40, 128};
  options.seed = 8;
  options.peak_frequency_hz = peak_hz;
  options.snr = no_noise;
  auto clean = make_seismic(options);
  options.snr = 1.0;
  auto noisy = make_seismic(options);
  const auto box = clean->geometry().bounds();
  const auto a = clean->read(box), b = noisy->read(box);
  const std::int64_t nk = 128;
  std::vector<std::complex<double>> twiddle(static_cast<std::size_t>(nk));
  for (std::int64_t n = 0; n < nk; ++n)
    twiddle[static_cast<std::size_t>(n)] =
        std::polar(1.0, -2.0 * std::numbers::pi * static_cast<double>(n) / static_cast<double>(nk));
  std::vector<double> power(nk / 2 + 1, 0.0);
  for (std::int64_t i = 0; i < 40; i += 2)
    for (std::int64_t j = 0; j < 40; j += 2)
      for (std::int64_t f = 0; f <= nk / 2; ++f) {
        std::complex<double> sum = 0.0;
        for (std::int64_t k = 0; k < nk; ++k) {
          const auto at = box.offset({i, j, k});
          sum += static_cast<double>(b[at] - a[at]) * twiddle[static_cast<std::size_t>((f * k) % nk)];
        }
        power[static_cast<std::size_t>(f)] += std::norm(sum);
      }
  const auto peak = std::max_element(power.begin(), power.end()) - power.begin();
  return static_cast<double>(peak) / (static_cast<double>(nk) * 0.004);
}

TEST(SeismicCube, NoiseSpectrumPeaksAtTheWaveletFrequency) {
  const double bin = 1.0 / (128 * 0.004); // 1.95 Hz
  EXPECT_NEAR(noise_peak_frequency(30.0), 30.0, 2.0 * bin);
  EXPECT_NEAR(noise_peak_frequency(45.0), 45.0, 2.0 * bin);
}

TEST(SeismicCube, EveryCubeHasTheSpecialBodies) {
  for (const volume::Index3& shape :
       {volume::Index3{40, 40, 40}, volume::Index3{48, 40, 64}, volume::Index3{128, 96, 64}})
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      SeismicOptions options;
      options.shape = shape;
      options.seed = seed;
      auto cube = make_seismic(options);
      const auto& truth = cube->truth();
      int spots = 0, channels = 0, lobes = 0, cut = 0, centre = 0;
      for (const auto& b : truth.bodies) {
        spots += b.negative_control;
        channels += b.type == BodyType::channel;
        lobes += b.type == BodyType::lobe;
        cut += b.cut_by_border && b.chaotic;
        bool all_mid = true;
        for (int a = 0; a < 3; ++a)
          all_mid = all_mid && b.bounds_lo[a] < static_cast<double>(shape[a] / 2) &&
                    b.bounds_hi[a] > static_cast<double>(shape[a] / 2);
        centre += all_mid && b.type == BodyType::channel;
        EXPECT_GT(b.volume_voxels, 0.0);
        EXPECT_GE(b.azimuth_deg, 0.0);
        EXPECT_LT(b.azimuth_deg, 180.0);
        EXPECT_EQ(b.volume_exact, !b.negative_control);
        if (b.chaotic && !b.cut_by_border) {
          EXPECT_GT(b.volume_voxels, truth.bubble_volume_threshold_voxels) << b.name;
        }
      }
      EXPECT_EQ(spots, 1) << "seed " << seed;
      EXPECT_GE(channels, 1) << "seed " << seed;
      EXPECT_GE(lobes, 2) << "seed " << seed;
      EXPECT_GE(cut, 1) << "seed " << seed;
      EXPECT_EQ(centre, 1) << "seed " << seed;
      const auto& s = *truth.seismic;
      EXPECT_GT(s.chaotic_rms, 1.25 * s.background_rms); // thin bodies of small cubes take the layers' tails
      EXPECT_GT(s.rms_threshold_suggestion, s.background_rms);
      EXPECT_LT(s.rms_threshold_suggestion, std::sqrt(s.chaotic_rms * s.chaotic_rms + s.noise_rms * s.noise_rms));
    }
}

} // namespace
} // namespace geotandem::synth
