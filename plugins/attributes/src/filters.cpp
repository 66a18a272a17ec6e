#include "filters.hpp"
#include "geotandem/core/simd.hpp"

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

// Outputs o[k .. k + 8 V): o = w0 c (even) or 0 (odd), then o += w_t (plus_t +- minus_t) for
// t = 1, 2, ..., radius in that order. The V sums stay in registers over all the taps (one load
// and one store of o, not one per tap), and V > 1 lets their additions overlap.
// `neighbours(t)` gives the pointers {plus_t, minus_t} at output 0.
template <bool Even, int V, class Neighbours>
[[gnu::always_inline]] inline void filter_block(const float* centre, const Neighbours& neighbours, const float* w,
                                                int radius, float* o, std::size_t k) {
  // Loads and stores go through memcpy (unaligned, one instruction each); no function takes or
  // returns a Float8, whose passing would differ between the clones.
  Float8 sum[V];
  for (int v = 0; v < V; ++v) {
    sum[v] = Float8{};
    if (Even) {
      Float8 c;
      std::memcpy(&c, centre + k + kLanes * v, sizeof c);
      sum[v] = w[0] * c;
    }
  }
  for (int t = 1; t <= radius; ++t) {
    const float wt = w[t];
    if (wt == 0.0f) continue;
    const auto [a, b] = neighbours(t);
    for (int v = 0; v < V; ++v) {
      Float8 x, y;
      std::memcpy(&x, a + k + kLanes * v, sizeof x);
      std::memcpy(&y, b + k + kLanes * v, sizeof y);
      sum[v] += wt * (Even ? x + y : x - y);
    }
  }
  std::memcpy(o + k, sum, sizeof sum);
}

// The same sums for all of o[0 .. n): blocks of 32, then of 8, then one output at a time.
template <bool Even, class Neighbours>
[[gnu::always_inline]] inline void filter_outputs(const float* centre, const Neighbours& neighbours,
                                                  const Kernel& kernel, float* o, std::size_t n) {
  const float* w = kernel.half.data();
  const int radius = kernel.radius();
  std::size_t k = 0;
  for (; k + 4 * kLanes <= n; k += 4 * kLanes)
    filter_block<Even, 4>(centre, neighbours, w, radius, o, k);
  for (; k + kLanes <= n; k += kLanes)
    filter_block<Even, 1>(centre, neighbours, w, radius, o, k);
  for (; k < n; ++k) {
    float sum = Even ? w[0] * centre[k] : 0.0f;
    for (int t = 1; t <= radius; ++t) {
      const float wt = w[t];
      if (wt == 0.0f) continue;
      const auto [a, b] = neighbours(t);
      sum += wt * (Even ? a[k] + b[k] : a[k] - b[k]);
    }
    o[k] = sum;
  }
}

// n outputs from the inputs at `centre`, whose neighbours along the filtered axis are `stride`
// floats apart.
GEOTANDEM_AVX2_CLONES void filter_line(const float* centre, std::ptrdiff_t stride, const Kernel& kernel,
                                       float* __restrict o, std::size_t n) {
  const auto neighbours = [centre, stride](int t) { return std::pair{centre + t * stride, centre - t * stride}; };
  if (kernel.symmetry == Symmetry::even)
    filter_outputs<true>(centre, neighbours, kernel, o, n);
  else
    filter_outputs<false>(centre, neighbours, kernel, o, n);
}

// filter_line with the neighbours given as pointers (planes[radius +- t]) rather than a stride.
GEOTANDEM_AVX2_CLONES void filter_across(const float* const* planes, const Kernel& kernel, float* __restrict o,
                                         std::size_t n) {
  const int radius = kernel.radius();
  const auto neighbours = [planes, radius](int t) { return std::pair{planes[radius + t], planes[radius - t]}; };
  if (kernel.symmetry == Symmetry::even)
    filter_outputs<true>(planes[radius], neighbours, kernel, o, n);
  else
    filter_outputs<false>(planes[radius], neighbours, kernel, o, n);
}

} // namespace

void correlate_planes(const float* const* planes, const Kernel& kernel, float* out, std::size_t n) {
  filter_across(planes, kernel, out, n);
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
  shape[axis] -= 2 * kernel.radius();
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
  shape[axis] -= 2 * radius;
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
  for (std::int64_t i = 0; i < shape[0]; ++i)
    for (std::int64_t j = 0; j < shape[1]; ++j) {
      filter_line(in + (i * in_nj + j) * in_nk + offset[2], stride, kernel, o, nk);
      o += nk;
    }
  return shape;
}

} // namespace geotandem::attributes::detail
