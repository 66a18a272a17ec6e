#include "filters.hpp"
#include "geotandem/core/simd.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace geotandem::attributes::detail {
namespace {

// One output line along axis 2: `centre` points at the input sample under o[0]; neighbours along
// the filtered axis are `stride` floats apart. Loops run over k innermost so they vectorise, and
// each o[k] accumulates its taps in the fixed order t = 1, 2, ..., radius.
GEOTANDEM_AVX2_CLONES void filter_line(const float* centre, std::ptrdiff_t stride, const Kernel& kernel,
                                       float* __restrict o, std::size_t n) {
  const float* w = kernel.half.data();
  const int radius = kernel.radius();
  if (kernel.symmetry == Symmetry::even) {
    const float w0 = w[0];
    for (std::size_t k = 0; k < n; ++k)
      o[k] = w0 * centre[k];
    for (int t = 1; t <= radius; ++t) {
      const float wt = w[t];
      if (wt == 0.0f) continue;
      const float* a = centre + t * stride;
      const float* b = centre - t * stride;
      for (std::size_t k = 0; k < n; ++k)
        o[k] += wt * (a[k] + b[k]);
    }
  } else {
    for (std::size_t k = 0; k < n; ++k)
      o[k] = 0.0f;
    for (int t = 1; t <= radius; ++t) {
      const float wt = w[t];
      if (wt == 0.0f) continue;
      const float* a = centre + t * stride;
      const float* b = centre - t * stride;
      for (std::size_t k = 0; k < n; ++k)
        o[k] += wt * (a[k] - b[k]);
    }
  }
}

// filter_line with the neighbours given as pointers (planes[radius +- t]) rather than a stride.
GEOTANDEM_AVX2_CLONES void filter_across(const float* const* planes, const Kernel& kernel, float* __restrict o,
                                         std::size_t n) {
  const float* w = kernel.half.data();
  const int radius = kernel.radius();
  const float* centre = planes[radius];
  const bool even = kernel.symmetry == Symmetry::even;
  if (even) {
    const float w0 = w[0];
    for (std::size_t k = 0; k < n; ++k)
      o[k] = w0 * centre[k];
  } else {
    for (std::size_t k = 0; k < n; ++k)
      o[k] = 0.0f;
  }
  for (int t = 1; t <= radius; ++t) {
    const float wt = w[t];
    if (wt == 0.0f) continue;
    const float* a = planes[radius + t];
    const float* b = planes[radius - t];
    if (even) {
      for (std::size_t k = 0; k < n; ++k)
        o[k] += wt * (a[k] + b[k]);
    } else {
      for (std::size_t k = 0; k < n; ++k)
        o[k] += wt * (a[k] - b[k]);
    }
  }
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
  for (std::int64_t i = 0; i < shape[0]; ++i)
    for (std::int64_t j = 0; j < shape[1]; ++j) {
      const float* centre = in + ((i + offset[0]) * in_nj + (j + offset[1])) * in_nk + offset[2];
      filter_line(centre, stride, kernel, o, nk);
      o += nk;
    }
  return shape;
}

} // namespace geotandem::attributes::detail
