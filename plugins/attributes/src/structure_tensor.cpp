#include "structure_tensor.hpp"

#include <algorithm>
#include <vector>

#include "mirror.hpp"

namespace geotandem::attributes::detail {
namespace {

// Rings of the last `size` planes of a stage, one ring per component (bank), each plane of
// `count` samples; slot(bank, p) holds plane p of that component. All the planes are in one
// array, consecutive ones an odd number of cache lines apart: planes of a power-of-two size (a
// tile of 64 x 64 samples is 16 KiB), each in its own allocation, would start on the same cache
// sets, and a filter across 13 of them, or the chaos of the 6 components, would evict its own
// inputs from the first-level cache (a filter across was four times slower, measured).
class PlaneRings {
public:
  PlaneRings(int banks, int size, std::size_t count)
      : size_(size), stride_(padded(count)),
        data_(static_cast<std::size_t>(banks) * static_cast<std::size_t>(size) * stride_) {}
  float* slot(int bank, std::int64_t p) {
    return data_.data() + static_cast<std::size_t>(std::int64_t{bank} * size_ + p % size_) * stride_;
  }
  // Pointers to planes first .. first + count - 1 of a bank, in order (count <= size).
  void window(int bank, std::int64_t first, int count, std::vector<const float*>& out) {
    out.resize(static_cast<std::size_t>(count));
    for (int t = 0; t < count; ++t)
      out[static_cast<std::size_t>(t)] = slot(bank, first + t);
  }

private:
  static constexpr std::size_t kLine = 16; // floats in a 64-byte cache line
  static std::size_t padded(std::size_t count) {
    const std::size_t lines = (count + kLine - 1) / kLine;
    return (lines % 2 == 0 ? lines + 1 : lines) * kLine;
  }

  int size_;
  std::size_t stride_;
  std::vector<float> data_;
};

} // namespace

void stream_structure_tensor(const volume::Volume& input, const volume::Box& box, const TensorFilters& f,
                             const std::function<void(std::int64_t, const TensorPlane&)>& plane) {
  const int rg = f.smooth.radius(), ra = f.across.radius();
  const Array3 u = read_mirrored(input, box, f.halo);
  const std::int64_t n1 = box.size(1), n2 = box.size(2);
  // Plane sizes: gradient planes are the box grown by the smoothing radii on axes 1 and 2.
  const std::int64_t g1 = n1 + 2 * std::int64_t{ra}, g2 = n2 + 2 * std::int64_t{f.along.radius()};
  const auto grad_count = static_cast<std::size_t>(g1 * g2), out_count = static_cast<std::size_t>(n1 * n2);
  const std::int64_t input_planes = u.shape[0]; // n0 + 2 (rg + ra)

  // The planes go in batches of up to kBatch: each filter across axis 0 makes a batch's output
  // planes together (correlate_planes), so its rings hold 2 radius + kBatch planes.
  constexpr int kBatch = 4;
  // Stage 1 (per input plane): smoothed/derived along axes 2 then 1: aa, ab, ba.
  const int partial_size = 2 * rg + kBatch, smoothed_size = 2 * ra + kBatch;
  PlaneRings partial(3, partial_size, grad_count);
  // Stage 2 (per gradient plane): the 6 products smoothed along axes 2 then 1.
  PlaneRings smoothed(6, smoothed_size, out_count);
  static constexpr int pairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};

  // Stage-1 planes after the filter along the trace: u's rows, g2 samples each.
  Array3 a({1, u.shape[1], g2}), b({1, u.shape[1], g2}), product({1, g1, g2}), along_k({1, g1, n2});
  PlaneRings grad(3, kBatch, grad_count), tensor(6, kBatch, out_count);
  std::vector<const float*> window;
  std::vector<float*> outs;
  // Planes first .. first + count - 1 of `to`'s bank c from those of `from`'s, filtered across.
  const auto across = [&](PlaneRings& from, int c, std::int64_t first, const Kernel& kernel, PlaneRings& to,
                          std::int64_t count, std::size_t n) {
    from.window(c, first, static_cast<int>(2 * std::int64_t{kernel.radius()} + count), window);
    outs.resize(static_cast<std::size_t>(count));
    for (std::int64_t t = 0; t < count; ++t)
      outs[static_cast<std::size_t>(t)] = to.slot(c, first + t);
    correlate_planes(window.data(), kernel, outs.data(), n, static_cast<int>(count));
  };

  const volume::Index3 plane_shape{1, u.shape[1], u.shape[2]};
  const std::size_t plane_count = static_cast<std::size_t>(u.shape[1] * u.shape[2]);
  std::int64_t next_gradient = 0, next_output = 0; // the first plane of each stage not made yet
  for (std::int64_t first = 0; first < input_planes; first += kBatch) {
    const std::int64_t end = std::min(first + kBatch, input_planes);
    for (std::int64_t p = first; p < end; ++p) {
      const float* up = u.data.get() + static_cast<std::size_t>(p) * plane_count;
      a.shape = correlate(up, plane_shape, 2, f.smooth, a.data.get());
      b.shape = correlate(up, plane_shape, 2, f.derive, b.data.get());
      correlate(a.data.get(), a.shape, 1, f.smooth, partial.slot(0, p));
      correlate(a.data.get(), a.shape, 1, f.derive, partial.slot(1, p));
      correlate(b.data.get(), b.shape, 1, f.smooth, partial.slot(2, p));
    }

    // Gradient planes q up to end - 1 - 2 rg: across axis 0, derivative for component 0.
    const std::int64_t gradients = end - 2 * std::int64_t{rg} - next_gradient;
    if (gradients <= 0) continue;
    const std::int64_t q0 = next_gradient;
    across(partial, 0, q0, f.derive, grad, gradients, grad_count);
    across(partial, 1, q0, f.smooth, grad, gradients, grad_count);
    across(partial, 2, q0, f.smooth, grad, gradients, grad_count);
    for (std::int64_t q = q0; q < q0 + gradients; ++q)
      for (int c = 0; c < 6; ++c) {
        const float* x = grad.slot(pairs[c][0], q);
        const float* y = grad.slot(pairs[c][1], q);
        float* pr = product.data.get();
        for (std::size_t n = 0; n < grad_count; ++n)
          pr[n] = x[n] * y[n];
        correlate(product.data.get(), product.shape, 2, f.along, along_k.data.get());
        correlate(along_k.data.get(), along_k.shape, 1, f.across, smoothed.slot(c, q));
      }
    next_gradient += gradients;

    // Output planes o up to next_gradient - 1 - 2 ra: tensor smoothing across axis 0.
    const std::int64_t outputs = next_gradient - 2 * std::int64_t{ra} - next_output;
    if (outputs <= 0) continue;
    for (int c = 0; c < 6; ++c)
      across(smoothed, c, next_output, f.across, tensor, outputs, out_count);
    for (std::int64_t o = next_output; o < next_output + outputs; ++o) {
      TensorPlane result{};
      for (int c = 0; c < 6; ++c)
        result[static_cast<std::size_t>(c)] = tensor.slot(c, o);
      plane(o, result);
    }
    next_output += outputs;
  }
}

} // namespace geotandem::attributes::detail
