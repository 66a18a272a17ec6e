// The seismic kind: noiseless traces from the model (seismic_model.cpp) plus band-limited noise
// (white noise per sample, convolved with the wavelet along the trace and with a 3x3 binomial
// kernel across traces, in floats).

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "geotandem/core/error.hpp"
#include "geotandem/core/simd.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "hash.hpp"
#include "seismic_model.hpp"
#include "validate.hpp"
#include "white_noise.hpp"

namespace geotandem::synth {
namespace detail {

// Four samples at a time: the 64-bit multiplications of the hash as vectors, and the top 53 bits
// made a double exactly (52 of them as a mantissa, the last added as 2^-53), so every value has
// the bits of the scalar formula.
GEOTANDEM_AVX2_CLONES void white_noise(std::uint64_t trace_key, std::int64_t k0, std::int64_t n, float* out) {
  using U64x4 = std::uint64_t __attribute__((vector_size(32)));
  using F64x4 = double __attribute__((vector_size(32)));
  using F32x4 = float __attribute__((vector_size(16)));
  constexpr double lo = -1.7320508075688772, hi = 1.7320508075688772;
  const U64x4 lanes = {0u, 1u, 2u, 3u};
  const U64x4 one = {0x3ff0000000000000u, 0x3ff0000000000000u, 0x3ff0000000000000u, 0x3ff0000000000000u};
  const std::uint64_t half_ulp = std::bit_cast<std::uint64_t>(0x1.0p-53);
  std::int64_t k = 0;
  for (; k + 4 <= n; k += 4) {
    U64x4 x = trace_key ^ (static_cast<std::uint64_t>(k0 + k) + lanes); // hash1, then mix64
    x += 0x9e3779b97f4a7c15u;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9u;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebu;
    x = x ^ (x >> 31);
    const F64x4 high = reinterpret_cast<F64x4>((x >> 12) | one) - 1.0; // (x >> 12) 2^-52
    const F64x4 low = reinterpret_cast<F64x4>((0u - ((x >> 11) & 1u)) & half_ulp);
    const F64x4 value = lo + (hi - lo) * (high + low);
    const F32x4 rounded = __builtin_convertvector(value, F32x4);
    std::memcpy(out + k, &rounded, sizeof rounded);
  }
  for (; k < n; ++k)
    out[k] = static_cast<float>(uniform(hash1(trace_key, k0 + k), lo, hi));
}

namespace {

// Eight floats as one value (a GCC/Clang vector extension); loads and stores go through memcpy.
using Float8 = float __attribute__((vector_size(32)));
constexpr std::int64_t kLanes = 8;

// out[k] = w[0] in[k] + sum over d = 1 .. radius of w[d] (in[k - d] + in[k + d]) for k < n (a
// multiple of 8), in that order: a symmetric filter, in[-radius .. n + radius) readable.
GEOTANDEM_AVX2_CLONES void symmetric_filter(const float* in, const float* w, std::int64_t radius, std::int64_t n,
                                            float* out) {
  for (std::int64_t k = 0; k < n; k += kLanes) {
    Float8 c;
    std::memcpy(&c, in + k, sizeof c);
    Float8 sum = w[0] * c;
    for (std::int64_t d = 1; d <= radius; ++d) {
      Float8 before, after;
      std::memcpy(&before, in + k - d, sizeof before);
      std::memcpy(&after, in + k + d, sizeof after);
      sum += w[d] * (before + after);
    }
    std::memcpy(out + k, &sum, sizeof sum);
  }
}

// out[k] = 0.25 a[k] + 0.5 b[k] + 0.25 c[k] for k < n (a multiple of 8): the binomial 1-2-1.
GEOTANDEM_AVX2_CLONES void binomial3(const float* a, const float* b, const float* c, std::int64_t n, float* out) {
  for (std::int64_t k = 0; k < n; k += kLanes) {
    Float8 x, y, z;
    std::memcpy(&x, a + k, sizeof x);
    std::memcpy(&y, b + k, sizeof y);
    std::memcpy(&z, c + k, sizeof z);
    const Float8 sum = 0.25f * x + 0.5f * y + 0.25f * z;
    std::memcpy(out + k, &sum, sizeof sum);
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
        if (model_.noise_scale > 0.0) slabs.add_noise(j - box.lo[1], signal.data());
        for (std::int64_t k = 0; k < nk; ++k)
          out[at++] = static_cast<float>(signal[static_cast<std::size_t>(k)]);
      }
    }
  }

private:
  // The noise of the box's traces, in floats: white noise per trace filtered by the wavelet along
  // it, then by the binomial 1-2-1 across crosslines (kept per inline) and across inlines (per
  // trace read). The three inlines around the current one are a rolling window, so that each
  // inline is filtered once per read. A sample's noise depends only on its trace and sample index.
  class NoiseSlabs {
  public:
    NoiseSlabs(const SeismicModel& model, const volume::Box& box)
        : model_(model), box_(box), nj_(box.size(1)), nk_(box.size(2)), stride_((nk_ + kLanes - 1) / kLanes * kLanes),
          radius_(model.wavelet.half_taps()) {
      for (auto& s : slab_)
        s.resize(static_cast<std::size_t>(nj_ * stride_));
      const auto& taps = model_.wavelet.taps;
      for (std::int64_t d = 0; d <= radius_; ++d)
        half_taps_.push_back(static_cast<float>(taps[static_cast<std::size_t>(radius_ + d)]));
      white_.resize(static_cast<std::size_t>(stride_ + 2 * radius_));
      filtered_.resize(static_cast<std::size_t>((nj_ + 2) * stride_));
      sum_.resize(static_cast<std::size_t>(stride_));
    }
    // Makes the slabs hold inlines i - 1, i, i + 1.
    void advance(std::int64_t i) {
      for (std::int64_t d = -1; d <= 1; ++d) {
        const std::int64_t want = i + d;
        const auto slot = static_cast<std::size_t>(((want % 3) + 3) % 3);
        if (held_[slot] == want) continue;
        fill(want, slab_[slot]);
        held_[slot] = want;
      }
      current_ = i;
    }
    // Adds the scaled noise of trace (current, box.lo[1] + jj) to `out`.
    void add_noise(std::int64_t jj, double* out) {
      const float* row[3];
      for (int di = 0; di < 3; ++di)
        row[di] = slab_[static_cast<std::size_t>((((current_ + di - 1) % 3) + 3) % 3)].data() + jj * stride_;
      binomial3(row[0], row[1], row[2], stride_, sum_.data());
      for (std::int64_t k = 0; k < nk_; ++k)
        out[k] += model_.noise_scale * static_cast<double>(sum_[static_cast<std::size_t>(k)]);
    }

  private:
    void fill(std::int64_t i, std::vector<float>& slab) {
      // The white noise the filter reads: a radius each side of the stride's samples.
      const std::int64_t k_white = box_.lo[2] - radius_;
      const std::int64_t n_white = static_cast<std::int64_t>(white_.size());
      const float* centre = white_.data() + radius_;
      for (std::int64_t jj = 0; jj < nj_ + 2; ++jj) {
        const std::uint64_t trace_key = hash2(model_.noise_key, i, box_.lo[1] - 1 + jj);
        white_noise(trace_key, k_white, n_white, white_.data());
        symmetric_filter(centre, half_taps_.data(), radius_, stride_, filtered_.data() + jj * stride_);
      }
      for (std::int64_t jj = 0; jj < nj_; ++jj)
        binomial3(filtered_.data() + jj * stride_, filtered_.data() + (jj + 1) * stride_,
                  filtered_.data() + (jj + 2) * stride_, stride_, slab.data() + jj * stride_);
    }

    const SeismicModel& model_;
    volume::Box box_;
    std::int64_t nj_, nk_, stride_, radius_;
    std::array<std::vector<float>, 3> slab_;
    std::vector<float> half_taps_, white_, filtered_, sum_;
    std::array<std::int64_t, 3> held_{std::numeric_limits<std::int64_t>::min(),
                                      std::numeric_limits<std::int64_t>::min(),
                                      std::numeric_limits<std::int64_t>::min()};
    std::int64_t current_ = 0;
  };

  SeismicModel model_;
};

// Tables the layers that traces can reach: samples -2h - 1 .. nk + 2h + 1 under every fold of the
// cube (the shift is affine, so it is extreme at the corners; the stretch lies in [1, 1 + sum of
// the bumps' heights]). Capped at 2^20 layers; a layer outside the table is computed on demand.
void table_layers(SeismicModel& model) {
  const auto& shape = model.frame.geometry().shape;
  double shift_lo = HUGE_VAL, shift_hi = -HUGE_VAL;
  for (const double i : {0.0, static_cast<double>(shape[0] - 1)})
    for (const double j : {0.0, static_cast<double>(shape[1] - 1)}) {
      const Vec3 p = model.frame.to_frame(i, j, 0.0);
      const double shift = model.fold.offset + model.fold.dip_x * p.x + model.fold.dip_y * p.y;
      shift_lo = std::min(shift_lo, shift);
      shift_hi = std::max(shift_hi, shift);
    }
  double stretch_hi = 1.0;
  for (const auto& b : model.fold.bumps)
    stretch_hi += std::max(0.0, b.height);
  const double reach = 2.0 * model.wavelet.half + 1.0;
  const double z_lo = -reach - shift_hi, z_hi = static_cast<double>(shape[2]) + reach - shift_lo;
  const double m_lo = std::min(z_lo, z_lo / stretch_hi) / model.spacing - 2.0;
  const double m_hi = std::max(z_hi, z_hi / stretch_hi) / model.spacing + 2.0;
  const double most = 1048576.0;
  if (!(m_hi - m_lo < most)) return;
  model.table_layers(static_cast<std::int64_t>(std::floor(m_lo)), static_cast<std::int64_t>(std::ceil(m_hi)) + 1);
}

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
  detail::table_layers(model);
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
