#include "seismic_model.hpp"
#include "geotandem/core/simd.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <numbers>

#include "fast_exp.hpp"
#include "hash.hpp"

namespace geotandem::synth::detail {
namespace {

// exp(-a x^2) < 1e-7 beyond the support.
constexpr double support_log = 16.11809565095832; // ln(1e7)

// For each spike, exp(-a x^2) and exp(-a (2 x + 1)) at x = first - position, where the recurrence
// along its support starts. Straight-line, so it vectorises (with an AVX2 clone).
GEOTANDEM_AVX2_CLONES void exponentials(double a, const double* __restrict first, const double* __restrict position,
                                        double* __restrict g, double* __restrict ratio, std::size_t n) {
  for (std::size_t m = 0; m < n; ++m) {
    const double x = first[m] - position[m];
    g[m] = fast_exp(-a * x * x);
    ratio[m] = fast_exp(-a * (2.0 * x + 1.0));
  }
}

using Lanes = double __attribute__((vector_size(32))); // four taps (two SSE registers by default)
using Mask = std::int64_t __attribute__((vector_size(32)));

// Adds every spike's Ricker values to ext, spike after spike in collection order, each along its
// support [first, last] (ext[0] is sample `origin`). Tap t = first + 4 q + l of a spike is lane l
// of step q: the first four taps come from g and ratio by the two-term recurrence
// (g_{t+1} = g_t r_t, r_{t+1} = r_t e^{-2a}), and each lane then steps four taps at a time,
// g_{t+4} = g_t R_t with R_t = r_t r_{t+1} r_{t+2} r_{t+3} and R_{t+4} = R_t e^{-32a}. A tap's
// value depends only on its spike and its index in the support, never on the samples read.
// (Steps aligned to multiples of 4 samples, with the lanes outside the support masked, were 5 %
// slower: the store of one spike forwarded whole to the next one's load did not pay for the
// extra step.)
GEOTANDEM_AVX2_CLONES void add_supports(double a, double step2, double step32, const double* __restrict position,
                                        const double* __restrict amplitude, const double* __restrict first,
                                        const double* __restrict last, const double* __restrict g0,
                                        const double* __restrict ratio0, std::size_t n, std::int64_t origin,
                                        double* __restrict ext) {
  const Lanes four = {4.0, 4.0, 4.0, 4.0};
  static constexpr Mask below[4] = {{0, 0, 0, 0}, {-1, 0, 0, 0}, {-1, -1, 0, 0}, {-1, -1, -1, 0}}; // lanes < n
  for (std::size_t m = 0; m < n; ++m) {
    const double r0 = ratio0[m], r1 = r0 * step2, r2 = r1 * step2, r3 = r2 * step2;
    const double g1 = g0[m] * r0, g2 = g1 * r1, g3 = g2 * r2;
    const double big = r0 * r1 * r2 * r3, step8 = step2 * step2 * step2 * step2;
    const double amp = amplitude[m];
    Lanes g = {amp * g0[m], amp * g1, amp * g2, amp * g3};
    Lanes ratio = {big, big * step8, big * step8 * step8, big * step8 * step8 * step8};
    const double x0 = first[m] - position[m];
    Lanes x = {x0, x0 + 1.0, x0 + 2.0, x0 + 3.0};
    const auto taps = static_cast<std::int64_t>(last[m] - first[m]) + 1;
    double* out = ext + (static_cast<std::int64_t>(first[m]) - origin);
    std::int64_t t = 0;
    for (; t + 4 <= taps; t += 4) {
      const Lanes v = g * (1.0 - 2.0 * a * x * x);
      Lanes sum;
      std::memcpy(&sum, out + t, sizeof sum);
      sum += v;
      std::memcpy(out + t, &sum, sizeof sum);
      g *= ratio;
      ratio *= step32;
      x += four;
    }
    // The last 0 to 3 taps, with zeros in the lanes past the support (ext has room for them).
    Lanes v = g * (1.0 - 2.0 * a * x * x);
    v = reinterpret_cast<Lanes>(reinterpret_cast<Mask>(v) & below[taps - t]);
    Lanes sum;
    std::memcpy(&sum, out + t, sizeof sum);
    sum += v;
    std::memcpy(out + t, &sum, sizeof sum);
  }
}

struct Spikes {
  std::vector<double> position, amplitude, first, last, g, ratio, ext;
  // Room for n spikes (grows only, so that a warm thread allocates nothing).
  void resize(std::size_t n) {
    if (n <= position.size()) return;
    for (auto* v : {&position, &amplitude, &first, &last, &g, &ratio})
      v->resize(n);
  }
};

// Per-thread scratch, so that a trace allocates nothing once warm. Not inlined: inlined, GCC looked
// the thread-local address up again (__tls_get_addr) at every use in trace().
[[gnu::noinline]] Spikes& spikes_scratch() {
  thread_local Spikes spikes;
  return spikes;
}

} // namespace

Wavelet::Wavelet(double peak_frequency_hz, double dt_s) {
  const double pf = std::numbers::pi * peak_frequency_hz * dt_s;
  a = pf * pf;
  step2 = std::exp(-2.0 * a);
  step32 = std::exp(-32.0 * a);
  half = std::sqrt(support_log / a);
  const int n = static_cast<int>(std::floor(half));
  for (int x = -n; x <= n; ++x)
    taps.push_back((*this)(static_cast<double>(x)));
}

double Wavelet::operator()(double x) const {
  const double ax2 = a * x * x;
  return (1.0 - 2.0 * ax2) * std::exp(-ax2);
}

void Fold::at(const Vec3& p, double& stretch, double& shift) const {
  double sum = 0.0;
  for (const auto& b : bumps) {
    const double dx = p.x - b.x, dy = p.y - b.y;
    sum += b.height * std::exp(-(dx * dx + dy * dy) / (2.0 * b.sigma * b.sigma));
  }
  stretch = 1.0 + sum;
  shift = offset + dip_x * p.x + dip_y * p.y;
}

double Channel::volume(double arc_length) const {
  return arc_length * 4.0 / 3.0 * half_width * depth;
}

Aabb Channel::bounds(const Frame& frame) const {
  Aabb box = line.bounds(frame, half_width, 0.0);
  box.lo[2] = top;
  box.hi[2] = top + depth;
  return box;
}

double Lobe::volume() const {
  return std::numbers::pi * a * b * thickness / 2.0;
}

Aabb Lobe::bounds(const Frame& frame) const {
  auto e = frame.ellipse_extent(a, axes.ux, axes.uy, b, axes.vx, axes.vy);
  auto c = frame.to_index(centre);
  return Aabb{{c[0] - e[0], c[1] - e[1], centre.z}, {c[0] + e[0], c[1] + e[1], centre.z + thickness}};
}

double BrightSpot::weight(const Vec3& p) const {
  const double dx = p.x - centre.x, dy = p.y - centre.y;
  const double s = (dx * axes.ux + dy * axes.uy) / a, n = (dx * axes.vx + dy * axes.vy) / b;
  const double rho = std::sqrt(s * s + n * n);
  if (rho >= 1.0) return 0.0;
  if (rho <= 0.7) return amplitude;
  const double c = std::cos(0.5 * std::numbers::pi * (rho - 0.7) / 0.3); // smooth rim
  return amplitude * c * c;
}

Aabb BrightSpot::bounds(const Frame& frame, double half_height) const {
  auto e = frame.ellipse_extent(a, axes.ux, axes.uy, b, axes.vx, axes.vy);
  auto c = frame.to_index(centre);
  return Aabb{{c[0] - e[0], c[1] - e[1], centre.z - half_height}, {c[0] + e[0], c[1] + e[1], centre.z + half_height}};
}

SeismicModel::SeismicModel(const Frame& frame_in, const Wavelet& wavelet_in)
    : frame(frame_in), wavelet(wavelet_in),
      chaotic_grid({frame_in.geometry().shape[0], frame_in.geometry().shape[1], 1}, 16),
      spot_grid({frame_in.geometry().shape[0], frame_in.geometry().shape[1], 1}, 16) {}

void SeismicModel::compute_layer(std::int64_t m, double& tau, double& amplitude) const {
  const std::uint64_t r = hash1(reflector_key, m);
  tau = spacing * (static_cast<double>(m) + 0.8 * unit(r));
  amplitude = uniform(mix64(r), -1.0, 1.0);
}

void SeismicModel::table_layers(std::int64_t m0, std::int64_t m1) {
  layer_tau.clear();
  layer_amplitude.clear();
  layer_m0 = m0;
  std::vector<double> tau(static_cast<std::size_t>(m1 - m0)), amplitude(tau.size());
  for (auto m = m0; m < m1; ++m)
    compute_layer(m, tau[static_cast<std::size_t>(m - m0)], amplitude[static_cast<std::size_t>(m - m0)]);
  layer_tau = std::move(tau);
  layer_amplitude = std::move(amplitude);
}

void SeismicModel::intervals(std::int64_t i, std::int64_t j, std::vector<Interval>& out) const {
  out.clear();
  const Vec3 p = frame.to_frame(static_cast<double>(i), static_cast<double>(j), 0.0);
  for (std::uint32_t id : chaotic_grid.query(volume::Box{{i, j, 0}, {i + 1, j + 1, 1}})) {
    if (const auto* lobe = std::get_if<Lobe>(&chaotic[id])) {
      const double dx = p.x - lobe->centre.x, dy = p.y - lobe->centre.y;
      const double s = (dx * lobe->axes.ux + dy * lobe->axes.uy) / lobe->a;
      const double n = (dx * lobe->axes.vx + dy * lobe->axes.vy) / lobe->b;
      const double rho2 = s * s + n * n;
      if (rho2 < 1.0) out.push_back({lobe->centre.z, lobe->centre.z + lobe->thickness * (1.0 - rho2)});
      continue;
    }
    const auto& ch = std::get<Channel>(chaotic[id]);
    double s = 0.0, n = 0.0;
    ch.line.local(p, s, n);
    const double w = ch.half_width;
    if (std::abs(n) >= ch.line.amplitude + w || std::abs(s) >= ch.line.half_length + w) continue;
    if (std::abs(n - ch.line.offset(s)) * ch.line.lipschitz_factor >= w) continue;
    const double t = ch.line.nearest(s, n);
    const double ds = s - t, dn = n - ch.line.offset(t);
    const double d2 = ds * ds + dn * dn;
    if (d2 >= w * w || ch.line.end_distance(s, n) < 0.0) continue;
    out.push_back({ch.top, ch.top + ch.depth * (1.0 - d2 / (w * w))});
  }
}

void SeismicModel::describe(std::int64_t i, std::int64_t j, TraceInfo& out) const {
  intervals(i, j, out.inside);
  const Vec3 p = frame.to_frame(static_cast<double>(i), static_cast<double>(j), 0.0);
  fold.at(p, out.stretch, out.shift);
  out.spots.clear();
  for (std::uint32_t id : spot_grid.query(volume::Box{{i, j, 0}, {i + 1, j + 1, 1}})) {
    const double wgt = spots[id].weight(p);
    if (wgt > 0.0) out.spots.push_back({spots[id].centre.z, wgt});
  }
}

std::uint64_t SeismicModel::next_cache_id() {
  static std::atomic<std::uint64_t> last{0};
  return ++last;
}

const TraceInfo& SeismicModel::trace_info(std::int64_t i, std::int64_t j) const {
  // Per thread, direct-mapped on (i, j) mod 64: the traces of a 64 x 64 column of boxes, which a
  // consumer reading boxes down the sample axis asks for again and again.
  thread_local std::vector<TraceInfo> cache(std::size_t{64} * 64);
  thread_local TraceInfo scratch;
  if (cache_id == 0) {
    describe(i, j, scratch);
    return scratch;
  }
  TraceInfo& slot = cache[static_cast<std::size_t>(((i & 63) << 6) | (j & 63))];
  if (slot.model != cache_id || slot.i != i || slot.j != j) {
    slot.model = 0; // invalid until complete, should describe() throw
    describe(i, j, slot);
    slot.model = cache_id;
    slot.i = i;
    slot.j = j;
  }
  return slot;
}

GEOTANDEM_AVX2_CLONES void SeismicModel::trace(std::int64_t i, std::int64_t j, const TraceInfo& info, std::int64_t k0,
                                               std::int64_t k1, double* out) const {
  const auto count = static_cast<std::size_t>(k1 - k0);
  const double h = wavelet.half;
  const double lo = static_cast<double>(k0) - h, hi = static_cast<double>(k1 - 1) + h;
  // Adds spike (position, amplitude) to every sample it reaches. exp(-a x^2) runs along the support
  // by recurrences (two exp per spike instead of one per sample), always from the first sample of
  // the support, so a sample's value never depends on the box. Each sample receives its spikes in
  // one global order (layers by index, then chaotic spikes by body and index, then bright spots),
  // whatever box is read, so sums are bit-identical.
  // Spikes are collected first, the two exponentials of each computed in one vectorised pass
  // (exponentials()), then added in collection order (add_supports()).
  const std::vector<Interval>& inside = info.inside;
  auto in_chaotic = [&](double position) {
    for (const auto& iv : inside)
      if (position >= iv.top && position < iv.base) return true;
    return false;
  };
  const double stretch = info.stretch, shift = info.shift;
  // Layers m sit at geological time tau_m = spacing * (m + 0.8 u_m), increasing in m.
  const auto m_lo = static_cast<std::int64_t>(std::floor((lo - shift) / stretch / spacing)) - 1;
  const auto m_hi = static_cast<std::int64_t>(std::ceil((hi - shift) / stretch / spacing)) + 1;
  // Chaotic bodies: spikes at random positions per trace, with no lateral continuity, n_lo .. n_hi
  // of each interval.
  auto n_lo = [&](const Interval& iv) {
    return static_cast<std::int64_t>(std::floor(std::max(iv.top, lo) / spacing)) - 1;
  };
  auto n_hi = [&](const Interval& iv) {
    return static_cast<std::int64_t>(std::ceil(std::min(iv.base, hi + 1.0) / spacing));
  };
  std::size_t most = static_cast<std::size_t>(std::max<std::int64_t>(0, m_hi - m_lo + 1)) + info.spots.size();
  for (const auto& iv : inside)
    most += static_cast<std::size_t>(std::max<std::int64_t>(0, n_hi(iv) - n_lo(iv) + 1));

  Spikes& spikes = spikes_scratch();
  spikes.resize(most + 3);
  std::size_t count_spikes = 0;
  auto add = [&](double position, double amplitude) __attribute__((always_inline)) {
    const double first = std::ceil(position - h);
    const double last = std::floor(position + h);
    if (static_cast<std::int64_t>(last) < k0 || static_cast<std::int64_t>(first) >= k1) return;
    spikes.position[count_spikes] = position;
    spikes.amplitude[count_spikes] = amplitude;
    spikes.first[count_spikes] = first;
    spikes.last[count_spikes] = last;
    ++count_spikes;
  };
  for (auto m = m_lo; m <= m_hi; ++m) {
    double tau = 0.0, amplitude = 0.0;
    layer(m, tau, amplitude);
    const double position = tau * stretch + shift;
    if (position < lo || position > hi || in_chaotic(position)) continue;
    add(position, amplitude);
  }
  const std::uint64_t trace_key = hash2(chaotic_key, i, j);
  for (const auto& iv : inside)
    for (auto n = n_lo(iv); n <= n_hi(iv); ++n) {
      const std::uint64_t r = hash1(trace_key, n);
      const double position = spacing * (static_cast<double>(n) + unit(r));
      if (position < iv.top || position >= iv.base || position < lo || position > hi) continue;
      add(position, chaotic_amplitude * uniform(mix64(r), -1.0, 1.0));
    }
  for (const auto& [z, wgt] : info.spots)
    if (z >= lo && z <= hi) add(z, wgt);

  const double a = wavelet.a;
  // The exponentials for a whole number of vectors (four spikes: a scalar remainder cost as much as
  // the vectors before it); the spikes after the last are harmless zeros.
  const std::size_t padded = (count_spikes + 3) / 4 * 4;
  std::fill(spikes.first.begin() + static_cast<std::ptrdiff_t>(count_spikes),
            spikes.first.begin() + static_cast<std::ptrdiff_t>(padded), 0.0);
  std::fill(spikes.position.begin() + static_cast<std::ptrdiff_t>(count_spikes),
            spikes.position.begin() + static_cast<std::ptrdiff_t>(padded), 0.0);
  exponentials(a, spikes.first.data(), spikes.position.data(), spikes.g.data(), spikes.ratio.data(), padded);
  // The spikes' values go to a copy of the samples widened by a support each way, so that no
  // support is cut at k0 or k1 (a cut support would still add the same values to the samples kept).
  const auto reach = static_cast<std::int64_t>(std::ceil(2.0 * h)) + 1;
  spikes.ext.assign(count + 2 * static_cast<std::size_t>(reach) + 4, 0.0);
  add_supports(a, wavelet.step2, wavelet.step32, spikes.position.data(), spikes.amplitude.data(), spikes.first.data(),
               spikes.last.data(), spikes.g.data(), spikes.ratio.data(), count_spikes, k0 - reach, spikes.ext.data());
  std::copy_n(spikes.ext.data() + reach, count, out);
}

// After the cloned overload: clang refuses a function that becomes multiversioned after a use.
void SeismicModel::trace(std::int64_t i, std::int64_t j, std::int64_t k0, std::int64_t k1, double* out) const {
  trace(i, j, trace_info(i, j), k0, k1, out);
}

} // namespace geotandem::synth::detail
