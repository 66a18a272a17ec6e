#include "seismic_model.hpp"
#include "geotandem/core/simd.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
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

// values[t * n + m] = amplitude * (1 - 2 a x^2) g for spike m at tap t of its support, with g and
// ratio carried along the support by the recurrence g *= ratio, ratio *= step2, x += 1 (the loop
// over taps carries it, the loop over spikes vectorises).
GEOTANDEM_AVX2_CLONES void support_values(double a, double step2, const double* __restrict amplitude,
                                          double* __restrict x, double* __restrict g, double* __restrict ratio,
                                          double* __restrict values, std::size_t n, std::size_t taps) {
  for (std::size_t t = 0; t < taps; ++t) {
    double* __restrict row = values + t * n;
    for (std::size_t m = 0; m < n; ++m) {
      row[m] = amplitude[m] * (1.0 - 2.0 * a * x[m] * x[m]) * g[m];
      g[m] *= ratio[m];
      ratio[m] *= step2;
      x[m] += 1.0;
    }
  }
}

struct Spikes {
  std::vector<double> position, amplitude, first, g, ratio, x, values;
  void clear() {
    position.clear();
    amplitude.clear();
    first.clear();
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

SeismicModel::SeismicModel(const Frame& frame_, const Wavelet& wavelet_)
    : frame(frame_), wavelet(wavelet_), chaotic_grid({frame_.geometry().shape[0], frame_.geometry().shape[1], 1}, 16),
      spot_grid({frame_.geometry().shape[0], frame_.geometry().shape[1], 1}, 16) {}

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
  thread_local std::vector<TraceInfo> cache(64 * 64);
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

void SeismicModel::trace(std::int64_t i, std::int64_t j, std::int64_t k0, std::int64_t k1, double* out) const {
  trace(i, j, trace_info(i, j), k0, k1, out);
}

void SeismicModel::trace(std::int64_t i, std::int64_t j, const TraceInfo& info, std::int64_t k0, std::int64_t k1,
                         double* out) const {
  const auto count = static_cast<std::size_t>(k1 - k0);
  std::fill(out, out + count, 0.0);
  const double h = wavelet.half;
  const double lo = static_cast<double>(k0) - h, hi = static_cast<double>(k1 - 1) + h;
  // Adds spike (position, amplitude) to every sample it reaches. exp(-a x^2) runs along the support
  // by a two-term recurrence (three exp per spike instead of one per sample), always from the first
  // sample of the support, so a sample's value never depends on the box. Each sample receives its
  // spikes in one global order (layers by index, then chaotic spikes by body and index, then bright
  // spots), whatever box is read, so sums are bit-identical.
  // Spikes are collected first, the two exponentials of each computed in one vectorised pass
  // (exponentials()), then added in collection order.
  Spikes& spikes = spikes_scratch();
  spikes.clear();
  auto add = [&](double position, double amplitude) __attribute__((always_inline)) {
    const double first = std::ceil(position - h);
    const auto last = static_cast<std::int64_t>(std::floor(position + h));
    if (last < k0 || static_cast<std::int64_t>(first) >= k1) return;
    spikes.position.push_back(position);
    spikes.amplitude.push_back(amplitude);
    spikes.first.push_back(first);
  };
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
  for (auto m = m_lo; m <= m_hi; ++m) {
    const std::uint64_t r = hash1(reflector_key, m);
    const double tau = spacing * (static_cast<double>(m) + 0.8 * unit(r));
    const double position = tau * stretch + shift;
    if (position < lo || position > hi || in_chaotic(position)) continue;
    add(position, uniform(mix64(r), -1.0, 1.0));
  }
  // Chaotic bodies: spikes at random positions per trace, with no lateral continuity.
  const std::uint64_t trace_key = hash2(chaotic_key, i, j);
  for (const auto& iv : inside) {
    const double top = std::max(iv.top, lo), base = std::min(iv.base, hi + 1.0);
    for (auto n = static_cast<std::int64_t>(std::floor(top / spacing)) - 1;
         n <= static_cast<std::int64_t>(std::ceil(base / spacing)); ++n) {
      const std::uint64_t r = hash1(trace_key, n);
      const double position = spacing * (static_cast<double>(n) + unit(r));
      if (position < iv.top || position >= iv.base || position < lo || position > hi) continue;
      add(position, chaotic_amplitude * uniform(mix64(r), -1.0, 1.0));
    }
  }
  for (const auto& [z, wgt] : info.spots)
    if (z >= lo && z <= hi) add(z, wgt);

  const double a = wavelet.a, step2 = std::exp(-2.0 * a);
  const std::size_t count_spikes = spikes.position.size();
  spikes.g.resize(count_spikes);
  spikes.ratio.resize(count_spikes);
  exponentials(a, spikes.first.data(), spikes.position.data(), spikes.g.data(), spikes.ratio.data(), count_spikes);
  // Every spike's support has at most `taps` samples. Its values along the support, computed for all
  // spikes at once (tap-major, so the loop over spikes vectorises), by the same recurrence and in
  // the same operations as one spike at a time would use: the values are the same bits.
  const auto taps = static_cast<std::size_t>(std::floor(2.0 * h)) + 2;
  spikes.x.resize(count_spikes);
  spikes.values.resize(taps * count_spikes);
  for (std::size_t n = 0; n < count_spikes; ++n)
    spikes.x[n] = spikes.first[n] - spikes.position[n];
  support_values(a, step2, spikes.amplitude.data(), spikes.x.data(), spikes.g.data(), spikes.ratio.data(),
                 spikes.values.data(), count_spikes, taps);
  // Added to the samples spike after spike, in collection order: each sample sums its spikes in
  // the same order whatever box is read.
  for (std::size_t n = 0; n < count_spikes; ++n) {
    const auto first = static_cast<std::int64_t>(spikes.first[n]);
    const auto last = std::min(static_cast<std::int64_t>(std::floor(spikes.position[n] + h)), k1 - 1);
    const double* v = spikes.values.data() + n;
    for (auto k = std::max(first, k0); k <= last; ++k)
      out[k - k0] += v[static_cast<std::size_t>(k - first) * count_spikes];
  }
}

} // namespace geotandem::synth::detail
