// The seismic kind: noiseless traces from the model (seismic_model.cpp) plus band-limited noise
// (white noise per sample, convolved with the wavelet along the trace and with a 3x3 binomial
// kernel across traces).

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "geotandem/core/error.hpp"
#include "geotandem/core/simd.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "hash.hpp"
#include "seismic_model.hpp"
#include "validate.hpp"

namespace geotandem::synth {
namespace detail {
namespace {

constexpr double binomial[3] = {0.25, 0.5, 0.25};

// out[k] = sum over t < terms of weights[t] * rows[t][k], for k < n, each sum from 0.0 in the order
// t = 0, 1, ... (the same operations as adding one weighted row after another), kept in registers
// for eight samples at a time (explicit vectors: left to itself the compiler vectorises over t).
GEOTANDEM_AVX2_CLONES void weighted_sum(double* __restrict out, const double* const* rows, const double* weights,
                                        std::size_t terms, std::int64_t n) {
  using Lanes = double __attribute__((vector_size(32))); // four samples (two SSE registers by default)
  std::int64_t k = 0;
  for (; k + 8 <= n; k += 8) {
    Lanes low = {0.0, 0.0, 0.0, 0.0}, high = low;
    for (std::size_t t = 0; t < terms; ++t) {
      const double w = weights[t];
      Lanes a, b;
      std::memcpy(&a, rows[t] + k, sizeof a);
      std::memcpy(&b, rows[t] + k + 4, sizeof b);
      low += w * a;
      high += w * b;
    }
    std::memcpy(out + k, &low, sizeof low);
    std::memcpy(out + k + 4, &high, sizeof high);
  }
  for (; k < n; ++k) {
    double acc = 0.0;
    for (std::size_t t = 0; t < terms; ++t)
      acc += weights[t] * rows[t][k];
    out[k] = acc;
  }
}
// RMS of the noise before scaling: unit-variance white noise through the wavelet taps (sum of
// squares) and the 3x3 binomial kernel (sum of squares 0.375 per axis).
double unit_noise_rms(const Wavelet& wavelet) {
  double sum = 0.0;
  for (double w : wavelet.taps)
    sum += w * w;
  return std::sqrt(sum) * 0.375;
}

class SeismicCube final : public SyntheticCube {
public:
  SeismicCube(GroundTruth truth, SeismicModel model) : SyntheticCube(std::move(truth)), model_(std::move(model)) {}

protected:
  void read_box(const volume::Box& box, std::span<float> out) const override {
    const auto nk = box.size(2);
    std::vector<double> signal(static_cast<std::size_t>(nk));
    NoiseSlabs slabs(model_, box);
    std::size_t at = 0;
    for (auto i = box.lo[0]; i < box.hi[0]; ++i) {
      if (model_.noise_scale > 0.0) slabs.advance(i);
      for (auto j = box.lo[1]; j < box.hi[1]; ++j) {
        model_.trace(i, j, box.lo[2], box.hi[2], signal.data());
        if (model_.noise_scale > 0.0) slabs.noise(j - box.lo[1], signal.data());
        for (std::int64_t k = 0; k < nk; ++k)
          out[at++] = static_cast<float>(signal[static_cast<std::size_t>(k)]);
      }
    }
  }

private:
  // Temporal convolutions of white noise for the three inlines around the current one, kept as a
  // rolling window so that each inline is convolved once per read.
  class NoiseSlabs {
  public:
    NoiseSlabs(const SeismicModel& model, const volume::Box& box)
        : model_(model), box_(box), nj_(box.size(1) + 2), nk_(box.size(2)) {
      for (auto& s : slab_)
        s.resize(static_cast<std::size_t>(nj_ * nk_));
    }
    // Makes the slabs hold inlines i - 1, i, i + 1.
    void advance(std::int64_t i) {
      for (std::int64_t d = -1; d <= 1; ++d) {
        const std::int64_t want = i + d;
        auto& slot = slab_[static_cast<std::size_t>(((want % 3) + 3) % 3)];
        auto& held = held_[static_cast<std::size_t>(((want % 3) + 3) % 3)];
        if (held == want) continue;
        fill(want, slot);
        held = want;
      }
      current_ = i;
    }
    // Adds the scaled noise of trace (current, box.lo[1] + jj) to `out`.
    void noise(std::int64_t jj, double* out) const {
      const double* rows[9];
      double weights[9];
      for (int di = 0; di < 3; ++di) {
        const auto& s = slab_[static_cast<std::size_t>((((current_ + di - 1) % 3) + 3) % 3)];
        for (int dj = 0; dj < 3; ++dj)
          rows[di * 3 + dj] = s.data() + (jj + dj) * nk_;
      }
      for (int n = 0; n < 9; ++n)
        weights[n] = binomial[n / 3] * binomial[n % 3];
      // Per sample the same sum in the same order (n = 0 .. 8), accumulated across the trace so
      // that the loop over samples vectorises.
      sum_.resize(static_cast<std::size_t>(nk_));
      weighted_sum(sum_.data(), rows, weights, 9, nk_);
      for (std::int64_t k = 0; k < nk_; ++k)
        out[k] += model_.noise_scale * sum_[static_cast<std::size_t>(k)];
    }

  private:
    void fill(std::int64_t i, std::vector<double>& slab) const {
      const auto& taps = model_.wavelet.taps;
      const std::int64_t h = model_.wavelet.half_taps();
      std::vector<double> white(static_cast<std::size_t>(nk_ + 2 * h));
      std::vector<const double*> rows(taps.size());
      for (std::size_t t = 0; t < taps.size(); ++t)
        rows[t] = white.data() + 2 * h - static_cast<std::int64_t>(t);
      for (std::int64_t jj = 0; jj < nj_; ++jj) {
        const std::uint64_t trace_key = hash2(model_.noise_key, i, box_.lo[1] - 1 + jj);
        for (std::int64_t n = 0; n < nk_ + 2 * h; ++n)
          white[static_cast<std::size_t>(n)] = uniform(hash1(trace_key, box_.lo[2] - h + n), -1.7320508075688772,
                                                       1.7320508075688772); // unit variance
        // The wavelet filter, sample k summing its taps t = 0 .. 2h in order (as a dot product
        // per sample would), with the loop over samples innermost so that it vectorises.
        weighted_sum(slab.data() + jj * nk_, rows.data(), taps.data(), taps.size(), nk_);
      }
    }

    const SeismicModel& model_;
    volume::Box box_;
    std::int64_t nj_, nk_;
    std::array<std::vector<double>, 3> slab_;
    std::array<std::int64_t, 3> held_{std::numeric_limits<std::int64_t>::min(),
                                      std::numeric_limits<std::int64_t>::min(),
                                      std::numeric_limits<std::int64_t>::min()};
    std::int64_t current_ = 0;
    mutable std::vector<double> sum_;
  };

  SeismicModel model_;
};

struct RmsFigures {
  double all = 0.0, background = 0.0, chaotic = 0.0;
};

// RMS of the noiseless signal on a grid of 16 x 16 traces (all of it, and away from chaotic
// bodies), and on the traces through the centres of chaotic bodies (inside them). Depends only on
// the model, so every box sees the same noise scale.
RmsFigures measure_rms(const SeismicModel& model, const GroundTruth& truth) {
  const auto& shape = model.frame.geometry().shape;
  const double h = model.wavelet.half;
  std::vector<double> trace(static_cast<std::size_t>(shape[2]));
  TraceInfo info; // described once per trace (the model is not complete: trace() keeps no cache yet)
  const std::vector<Interval>& inside = info.inside;
  double all = 0.0, background = 0.0, chaotic = 0.0;
  std::size_t n_all = 0, n_background = 0, n_chaotic = 0;
  for (int a = 0; a < 16; ++a)
    for (int b = 0; b < 16; ++b) {
      const std::int64_t i = (2 * a + 1) * shape[0] / 32, j = (2 * b + 1) * shape[1] / 32;
      model.describe(i, j, info);
      model.trace(i, j, info, 0, shape[2], trace.data());
      for (std::int64_t k = 0; k < shape[2]; ++k) {
        const double v = trace[static_cast<std::size_t>(k)];
        all += v * v;
        ++n_all;
        const double z = static_cast<double>(k);
        bool near = false;
        for (const auto& iv : inside)
          near = near || (z >= iv.top - h && z < iv.base + h);
        if (!near) {
          background += v * v;
          ++n_background;
        }
      }
    }
  for (const auto& body : truth.bodies) {
    if (!body.chaotic) continue;
    for (std::int64_t di = -2; di <= 2; ++di)
      for (std::int64_t dj = -2; dj <= 2; ++dj) {
        const auto i = static_cast<std::int64_t>(std::lround(body.centre_index[0])) + di;
        const auto j = static_cast<std::int64_t>(std::lround(body.centre_index[1])) + dj;
        if (i < 0 || j < 0 || i >= shape[0] || j >= shape[1]) continue;
        model.describe(i, j, info);
        // Only the samples inside: a sample's value does not depend on the range read, and a body
        // is a few tens of samples thick in a trace of thousands (the paper's cube has about
        // 68,000 chaotic bodies, whose whole traces took most of a minute in every process).
        for (const auto& iv : inside) {
          const std::int64_t k0 = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::ceil(iv.top)));
          const std::int64_t k1 = std::min<std::int64_t>(shape[2], static_cast<std::int64_t>(std::ceil(iv.base)));
          if (k1 <= k0) continue;
          model.trace(i, j, info, k0, k1, trace.data());
          for (std::int64_t k = 0; k < k1 - k0; ++k) {
            chaotic += trace[static_cast<std::size_t>(k)] * trace[static_cast<std::size_t>(k)];
            ++n_chaotic;
          }
        }
      }
  }
  auto rms = [](double sum, std::size_t n) { return n ? std::sqrt(sum / static_cast<double>(n)) : 0.0; };
  return {rms(all, n_all), rms(background, n_background), rms(chaotic, n_chaotic)};
}

} // namespace
} // namespace detail

std::unique_ptr<SyntheticCube> make_seismic(const SeismicOptions& options) {
  using detail::check_range;
  detail::check_shape("seismic cube shape", options.shape);
  if (options.survey.z_unit != volume::SampleUnit::milliseconds)
    throw InvalidArgument("synthetic seismic cubes are in time: survey.z_unit is 'm', it must be 'ms'", {},
                          "the Ricker wavelet is defined in time; use the analytic kind for depth cubes");
  detail::check_survey(options.survey);
  const double nyquist = 500.0 / options.survey.dz; // Hz, dz in ms
  check_range("peak_frequency_hz", options.peak_frequency_hz, {0.0, nyquist, true, true},
              "Hz (Nyquist for dz = " + std::to_string(options.survey.dz) + " ms)");
  check_range("snr", options.snr, {0.0, HUGE_VAL, true, false}, "(RMS signal / RMS noise; inf: no noise)");
  check_range("body_density", options.body_density, {0.0, 50.0}, "bodies per million samples");
  check_range("chaotic_gain", options.chaotic_gain, {1.0, 10.0});
  check_range("bright_spot_gain", options.bright_spot_gain, {1.0, 20.0});
  check_range("reflector_spacing", options.reflector_spacing, {1.5, 20.0}, "samples");

  detail::Frame frame(options.survey, options.shape);
  detail::Wavelet wavelet(options.peak_frequency_hz, options.survey.dz / 1000.0);
  auto layout = detail::layout_seismic(options, frame, wavelet);

  detail::SeismicModel model(frame, wavelet);
  model.reflector_key = detail::key(options.seed, detail::Stream::reflectors);
  model.chaotic_key = detail::key(options.seed, detail::Stream::chaotic);
  model.noise_key = detail::key(options.seed, detail::Stream::noise);
  model.fold = std::move(layout.fold);
  model.spacing = options.reflector_spacing;
  model.chaotic_amplitude = options.chaotic_gain; // same spike density inside and out: RMS ratio = gain
  model.chaotic = std::move(layout.chaotic);
  model.spots = std::move(layout.spots);
  const volume::Box cube2d{{0, 0, 0}, {options.shape[0], options.shape[1], 1}};
  // The traces a body's box covers (the grids are one sample deep).
  auto footprint = [&](detail::Aabb box) {
    box.lo[2] = 0.0;
    box.hi[2] = 0.0;
    return box.samples(cube2d);
  };
  for (std::size_t n = 0; n < model.chaotic.size(); ++n)
    std::visit(
        [&](const auto& body) { model.chaotic_grid.add(static_cast<std::uint32_t>(n), footprint(body.bounds(frame))); },
        model.chaotic[n]);
  for (std::size_t n = 0; n < model.spots.size(); ++n)
    model.spot_grid.add(static_cast<std::uint32_t>(n), footprint(model.spots[n].bounds(frame, 0.0)));
  model.chaotic_grid.seal();
  model.spot_grid.seal();

  const auto rms = detail::measure_rms(model, layout.truth);
  SeismicTruth s;
  s.peak_frequency_hz = options.peak_frequency_hz;
  s.snr = options.snr;
  s.signal_rms = rms.all;
  s.noise_rms = std::isfinite(options.snr) ? rms.all / options.snr : 0.0;
  s.background_rms = rms.background;
  s.chaotic_rms = rms.chaotic;
  s.wavelet_half_length = static_cast<int>(std::ceil(wavelet.half));
  const double n2 = s.noise_rms * s.noise_rms;
  s.rms_threshold_suggestion =
      std::sqrt(std::sqrt(rms.background * rms.background + n2) * std::sqrt(rms.chaotic * rms.chaotic + n2));
  model.noise_scale = s.noise_rms / detail::unit_noise_rms(wavelet);
  model.cache_id = detail::SeismicModel::next_cache_id(); // complete: traces may be cached from here
  layout.truth.seismic = s;
  return std::make_unique<detail::SeismicCube>(std::move(layout.truth), std::move(model));
}

} // namespace geotandem::synth
