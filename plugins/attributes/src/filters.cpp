#include "filters.hpp"
#include "geotandem/core/simd.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace geotandem::attributes::detail {
namespace {

// Eight floats as one value (a GCC/Clang vector extension): one register in the AVX2 clone, two
// in the default one. Lane by lane the arithmetic is that of plain floats, and neither clone may
// fuse a multiply with an add (no FMA), so every output has the same bits whichever clone runs.
using Float8 = float __attribute__((vector_size(32)));
constexpr std::size_t kLanes = 8;
// Eight floats at any address (one unaligned load or store). Loads and stores are written in
// place: no function takes or returns a Float8, whose passing would differ between the clones.
using UnalignedFloat8 = float __attribute__((vector_size(32), aligned(4), may_alias));

// The taps w(0 .. radius) of a kernel. With R > 0 the radius is known when compiling: the taps
// are copied into the object (the outputs' stores may not alias them, so they stay in registers
// across blocks), the loop over them is unrolled and none is tested against 0 (the dispatch below
// has checked that none is). With R = 0 they are read from the kernel and zero taps are skipped.
template <int R> struct Taps {
  explicit Taps(const Kernel& kernel) : radius(R > 0 ? R : kernel.radius()) {
    if constexpr (R > 0)
      std::memcpy(fixed, kernel.half.data(), sizeof fixed);
    else
      w = kernel.half.data();
  }
  Taps(const Taps&) = delete; // w may point into the object
  Taps& operator=(const Taps&) = delete;
  bool skip(float wt) const { return R == 0 && wt == 0.0f; }

  float fixed[R + 1];
  const float* w = fixed;
  int radius;
};

// Outputs o[k .. k + 8 V): o = w0 c (even) or 0 (odd), then o += w_t (plus_t +- minus_t) for
// t = 1, 2, ..., radius in that order, skipping zero taps. The V sums stay in registers over all
// the taps (one load and one store of o, not one per tap), and V > 1 lets their additions overlap.
// `neighbours(t)` gives the pointers {plus_t, minus_t} at output 0.
template <bool Even, int V, int R, class Neighbours>
[[gnu::always_inline]] inline void filter_block(const float* centre, const Neighbours& neighbours, const Taps<R>& taps,
                                                float* o, std::size_t k) {
  const float* w = taps.w;
  Float8 sum[V];
#pragma GCC unroll 4
  for (int v = 0; v < V; ++v)
    sum[v] = Even ? w[0] * *reinterpret_cast<const UnalignedFloat8*>(centre + k + kLanes * v) : Float8{};
#pragma GCC unroll 16
  for (int t = 1; t <= taps.radius; ++t) {
    const float wt = w[t];
    if (taps.skip(wt)) continue;
    const auto [a, b] = neighbours(t);
#pragma GCC unroll 4
    for (int v = 0; v < V; ++v) {
      const Float8 x = *reinterpret_cast<const UnalignedFloat8*>(a + k + kLanes * v);
      const Float8 y = *reinterpret_cast<const UnalignedFloat8*>(b + k + kLanes * v);
      sum[v] += wt * (Even ? x + y : x - y);
    }
  }
#pragma GCC unroll 4
  for (int v = 0; v < V; ++v)
    *reinterpret_cast<UnalignedFloat8*>(o + k + kLanes * v) = sum[v];
}

// Output k alone: the same sum as a block's lane.
template <bool Even, int R, class Neighbours>
[[gnu::always_inline]] inline float filter_one(const float* centre, const Neighbours& neighbours, const Taps<R>& taps,
                                               std::size_t k) {
  float sum = Even ? taps.w[0] * centre[k] : 0.0f;
  for (int t = 1; t <= taps.radius; ++t) {
    const float wt = taps.w[t];
    if (taps.skip(wt)) continue;
    const auto [a, b] = neighbours(t);
    sum += wt * (Even ? a[k] + b[k] : a[k] - b[k]);
  }
  return sum;
}

// Lines along one axis: `lines` lines of n outputs each, line L's centres at centre + L line_in
// and its outputs at o + L pitch; `neighbours(t)` gives the pointers {plus_t, minus_t} of line 0's
// output 0. Each line goes in blocks of 32, then of 8, then one output at a time.
template <class Neighbours> struct Lines {
  const float* centre;
  Neighbours neighbours;
  std::size_t line_in = 0, pitch = 0, n = 0, lines = 1;
  float* o;

  template <bool Even, int R> [[gnu::always_inline]] void filter(const Taps<R>& taps) const {
    float* out = o;
    for (std::size_t line = 0; line < lines; ++line, out += pitch) {
      const std::size_t shift = line * line_in;
      const float* c = centre + shift;
      const auto shifted = [this, shift](int t) {
        const auto [a, b] = neighbours(t);
        return std::pair{a + shift, b + shift};
      };
      std::size_t k = 0;
      for (; k + 4 * kLanes <= n; k += 4 * kLanes)
        filter_block<Even, 4>(c, shifted, taps, out, k);
      for (; k + kLanes <= n; k += kLanes)
        filter_block<Even, 1>(c, shifted, taps, out, k);
      for (; k < n; ++k)
        out[k] = filter_one<Even>(c, shifted, taps, k);
    }
  }
};

// Output planes b = 0 .. count - 1 of a filter across planes, outs[b] from planes[b .. b + 2 radius].
// The outputs go chunk by chunk, every output of a chunk before the next chunk: the input planes'
// chunks come from memory once and serve all the outputs from the first-level cache, where plane
// after plane would fetch every input plane 2 radius + 1 times.
struct Across {
  static constexpr int kMaxPlanes = 128; // 2 radius + count, at most (radius <= 60)
  // The planes' addresses in a local array, which the stores through `outs` cannot reach: they
  // stay in registers or are loaded once, not reloaded after every store.
  const float* planes[kMaxPlanes];
  float* const* outs;
  std::size_t n;
  int count;

  template <bool Even, int R> [[gnu::always_inline]] void filter(const Taps<R>& taps) const {
    const auto neighbours = [this, &taps](int b) {
      const float* const* p = planes + b + taps.radius;
      return [p](int t) { return std::pair{p[t], p[-t]}; };
    };
    const auto centre = [this, &taps](int b) { return planes[b + taps.radius]; };
    std::size_t k = 0;
    for (; k + 4 * kLanes <= n; k += 4 * kLanes)
      for (int b = 0; b < count; ++b)
        filter_block<Even, 4>(centre(b), neighbours(b), taps, outs[b], k);
    for (; k + kLanes <= n; k += kLanes)
      for (int b = 0; b < count; ++b)
        filter_block<Even, 1>(centre(b), neighbours(b), taps, outs[b], k);
    for (; k < n; ++k)
      for (int b = 0; b < count; ++b)
        outs[b][k] = filter_one<Even>(centre(b), neighbours(b), taps, k);
  }
};

// job.filter<even, R>(Taps<R>) with the radius fixed when compiling for the radii of the usual
// Gaussians (sigma up to 2: radius up to 6; sigma 3: radius 9) when no tap is 0; otherwise the
// general loop. Each output is the same sum in the same order either way.
template <int R, class Job> [[gnu::always_inline]] inline void filter_with(const Job& job, const Kernel& kernel) {
  const Taps<R> taps(kernel);
  if (kernel.symmetry == Symmetry::even)
    job.template filter<true>(taps);
  else
    job.template filter<false>(taps);
}

template <class Job> [[gnu::always_inline]] inline void filter_any(const Job& job, const Kernel& kernel) {
  const bool dense = std::find(kernel.half.begin() + 1, kernel.half.end(), 0.0f) == kernel.half.end();
  switch (dense ? kernel.radius() : 0) {
  case 1: return filter_with<1>(job, kernel);
  case 2: return filter_with<2>(job, kernel);
  case 3: return filter_with<3>(job, kernel);
  case 4: return filter_with<4>(job, kernel);
  case 5: return filter_with<5>(job, kernel);
  case 6: return filter_with<6>(job, kernel);
  case 9: return filter_with<9>(job, kernel);
  default: return filter_with<0>(job, kernel);
  }
}

// n outputs from the inputs at `centre`, whose neighbours along the filtered axis are `stride`
// floats apart.
GEOTANDEM_AVX2_CLONES void filter_line(const float* centre, std::ptrdiff_t stride, const Kernel& kernel,
                                       float* __restrict o, std::size_t n) {
  const auto neighbours = [centre, stride](int t) { return std::pair{centre + t * stride, centre - t * stride}; };
  filter_any(Lines<decltype(neighbours)>{centre, neighbours, 0, 0, n, 1, o}, kernel);
}

// `lines` lines along the innermost axis: line L's inputs start at centre + L line_in, its n
// outputs go to o + L pitch (n may exceed pitch: see correlate).
GEOTANDEM_AVX2_CLONES void filter_lines(const float* centre, std::size_t line_in, const Kernel& kernel,
                                        float* __restrict o, std::size_t pitch, std::size_t n, std::size_t lines) {
  const auto neighbours = [centre](int t) { return std::pair{centre + t, centre - t}; };
  filter_any(Lines<decltype(neighbours)>{centre, neighbours, line_in, pitch, n, lines, o}, kernel);
}

GEOTANDEM_AVX2_CLONES void filter_across(const float* const* planes, const Kernel& kernel, float* const* outs,
                                         std::size_t n, int count) {
  const int span = 2 * kernel.radius();
  if (span + count > Across::kMaxPlanes) { // more planes than the local array: in parts
    const int part = Across::kMaxPlanes - span;
    if (part < 1)
      throw std::logic_error("filter across planes: radius " + std::to_string(kernel.radius()) + " is too large");
    for (int b = 0; b < count; b += part)
      filter_across(planes + b, kernel, outs + b, n, std::min(part, count - b));
    return;
  }
  Across job{{}, outs, n, count};
  std::copy(planes, planes + span + count, job.planes);
  filter_any(job, kernel);
}

} // namespace

void correlate_planes(const float* const* planes, const Kernel& kernel, float* const* outs, std::size_t n, int count) {
  filter_across(planes, kernel, outs, n, count);
}

int gaussian_radius(double sigma) {
  return std::max(1, static_cast<int>(std::ceil(kTruncate * sigma)));
}

Kernel gaussian_kernel(double sigma) {
  const int radius = gaussian_radius(sigma);
  std::vector<double> g(static_cast<std::size_t>(radius) + 1);
  double sum = 0.0;
  for (int t = 0; t <= radius; ++t) {
    g[static_cast<std::size_t>(t)] = std::exp(-0.5 * t * t / (sigma * sigma));
    sum += (t == 0 ? 1.0 : 2.0) * g[static_cast<std::size_t>(t)];
  }
  Kernel kernel{{}, Symmetry::even};
  for (double v : g)
    kernel.half.push_back(static_cast<float>(v / sum));
  return kernel;
}

Kernel gaussian_derivative_kernel(double sigma) {
  const int radius = gaussian_radius(sigma);
  std::vector<double> d(static_cast<std::size_t>(radius) + 1);
  double moment = 0.0; // sum over t of t * w(t), both sides
  for (int t = 0; t <= radius; ++t) {
    d[static_cast<std::size_t>(t)] = t * std::exp(-0.5 * t * t / (sigma * sigma));
    moment += 2.0 * t * d[static_cast<std::size_t>(t)];
  }
  Kernel kernel{{}, Symmetry::odd};
  for (double v : d)
    kernel.half.push_back(static_cast<float>(v / moment));
  return kernel;
}

Kernel box_kernel(int radius) {
  return Kernel{std::vector<float>(static_cast<std::size_t>(radius) + 1, 1.0f), Symmetry::even};
}

Kernel hilbert_kernel(int half_length) {
  Kernel kernel{std::vector<float>(static_cast<std::size_t>(half_length) + 1, 0.0f), Symmetry::odd};
  const double pi = std::numbers::pi;
  for (int t = 1; t <= half_length; t += 2) {
    const double x = static_cast<double>(t) / (half_length + 1);
    const double window = 0.42 + 0.5 * std::cos(pi * x) + 0.08 * std::cos(2.0 * pi * x);
    // H[u](c) = sum over odd n of 2/(pi n) u(c - n); as a correlation the tap at +t is -2/(pi t).
    kernel.half[static_cast<std::size_t>(t)] = static_cast<float>(-2.0 / (pi * t) * window);
  }
  return kernel;
}

Array3 correlate(const Array3& in, int axis, const Kernel& kernel) {
  Array3 out;
  correlate(in, axis, kernel, out);
  return out;
}

void correlate(const Array3& in, int axis, const Kernel& kernel, Array3& out) {
  volume::Index3 shape = in.shape;
  shape[axis] -= 2 * std::int64_t{kernel.radius()};
  const auto needed = shape[axis] > 0 ? static_cast<std::size_t>(shape[0] * shape[1] * shape[2]) : 0;
  if (!out.data || out.count() != needed)
    out = Array3(shape[axis] > 0 ? shape : volume::Index3{0, 0, 0});
  else
    out.shape = shape;
  correlate(in.data.get(), in.shape, axis, kernel, out.data.get());
}

volume::Index3 correlate(const float* in, const volume::Index3& in_shape, int axis, const Kernel& kernel, float* out) {
  const int radius = kernel.radius();
  volume::Index3 shape = in_shape;
  shape[axis] -= 2 * std::int64_t{radius};
  if (shape[axis] <= 0)
    throw std::logic_error("filter of radius " + std::to_string(radius) + " along axis " + std::to_string(axis) +
                           " needs more than " + std::to_string(2 * radius) + " samples, got " +
                           std::to_string(in_shape[axis]));
  const std::int64_t in_nj = in_shape[1], in_nk = in_shape[2];
  const std::ptrdiff_t stride = axis == 0 ? in_nj * in_nk : axis == 1 ? in_nk : 1;
  volume::Index3 offset{0, 0, 0};
  offset[axis] = radius;
  const auto nk = static_cast<std::size_t>(shape[2]);
  float* o = out;
  if (axis != 2) {
    // Along axis 0 or 1 the lines keep their length, so the outputs of one plane (axis 1) or of
    // the whole array (axis 0) are one run of input samples shifted by radius strides: one call
    // over that run, whose blocks are long.
    const std::size_t run =
        axis == 0 ? static_cast<std::size_t>(shape[0] * shape[1]) * nk : static_cast<std::size_t>(shape[1]) * nk;
    const std::int64_t runs = axis == 0 ? 1 : shape[0];
    for (std::int64_t i = 0; i < runs; ++i) {
      filter_line(in + (i * in_nj + offset[1]) * in_nk + offset[0] * in_nj * in_nk, stride, kernel, o, run);
      o += run;
    }
    return shape;
  }
  // Along the lines (line L starts at L in_nk in the input, L nk in the output). Short lines would
  // leave many outputs to the one-at-a-time tail, so each line is rounded up to whole vectors where
  // that stays inside both arrays: the extra outputs read the next line's first samples and land
  // on the next line's first outputs, which that line writes again after (lines go in order, each
  // output its own sum, so the bits do not change).
  const auto lines = static_cast<std::size_t>(shape[0] * shape[1]);
  const auto line_in = static_cast<std::size_t>(in_nk);
  const std::size_t padded = (nk + kLanes - 1) / kLanes * kLanes;
  // Lines L with L step + reach <= total: the first ones.
  const auto lines_within = [lines](std::size_t step, std::size_t reach, std::size_t total) {
    return reach > total ? std::size_t{0} : std::min(lines, (total - reach) / step + 1);
  };
  // Lines 0 .. rounded - 1 have room for `padded` outputs, and for the inputs they read.
  const std::size_t rounded =
      std::min(lines_within(nk, padded, lines * nk),
               lines_within(line_in, padded + 2 * static_cast<std::size_t>(radius), lines * line_in));
  filter_lines(in + offset[2], line_in, kernel, out, nk, padded, rounded);
  filter_lines(in + offset[2] + rounded * line_in, line_in, kernel, out + rounded * nk, nk, nk, lines - rounded);
  return shape;
}

} // namespace geotandem::attributes::detail
