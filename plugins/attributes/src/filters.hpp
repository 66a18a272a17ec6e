#pragma once
// Separable 1D filters applied along one axis of an Array3, in "valid" mode: the output is the
// input shrunk by the kernel's radius on both ends of that axis, so no boundary rule is needed
// here (read_mirrored supplies the halo). Each output sample is summed in the same order
// whatever the array's extent, which is what makes a box bit-identical to the whole cube.

#include <vector>

#include "array3.hpp"

namespace geotandem::attributes::detail {

// Gaussian kernels are truncated at kTruncate standard deviations: radius = max(1, ceil(3 sigma)).
inline constexpr double kTruncate = 3.0;

enum class Symmetry {
  even, // w(-t) = w(t)
  odd,  // w(-t) = -w(t), w(0) = 0
};

// Taps w(0..radius); the other half follows from the symmetry. Applied as a correlation:
// out[c] = sum_t w(t) * in[c + t].
struct Kernel {
  std::vector<float> half;
  Symmetry symmetry = Symmetry::even;

  int radius() const { return static_cast<int>(half.size()) - 1; }
};

int gaussian_radius(double sigma);
// Sampled Gaussian, normalised to unit sum (a constant passes unchanged).
Kernel gaussian_kernel(double sigma);
// Sampled derivative of a Gaussian, normalised so that a unit ramp gives exactly 1 (sum t w(t) = 1).
Kernel gaussian_derivative_kernel(double sigma);
// All-ones kernel of the given radius: a moving sum over 2 radius + 1 samples.
Kernel box_kernel(int radius);
// Ideal discrete Hilbert transformer h(n) = 2 / (pi n) for odd n, tapered by a Blackman window
// reaching zero at |n| = half_length + 1, so that it maps cos to sin within the passband.
Kernel hilbert_kernel(int half_length);

// `in` filtered along `axis` (0, 1 or 2). Precondition: in.shape[axis] > 2 * kernel.radius().
Array3 correlate(const Array3& in, int axis, const Kernel& kernel);
// The same into `out`, whose storage is reused when it already holds as many samples.
void correlate(const Array3& in, int axis, const Kernel& kernel, Array3& out);
// The same on raw C-order storage: `in` of shape `in_shape`, `out` room for the result, whose shape
// is returned.
volume::Index3 correlate(const float* in, const volume::Index3& in_shape, int axis, const Kernel& kernel, float* out);

// Output planes of a filter across planes: outs[b] for b = 0 .. count - 1 from the consecutive
// planes planes[b .. b + 2 radius] of n samples each, its own plane being planes[b + radius]. Same
// sums in the same order as correlate along axis 0, so streaming plane by plane gives the same
// bits; several outputs at once read each input plane once for all of them.
void correlate_planes(const float* const* planes, const Kernel& kernel, float* const* outs, std::size_t n, int count);

} // namespace geotandem::attributes::detail
