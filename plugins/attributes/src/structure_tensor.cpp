#include "structure_tensor.hpp"

#include <vector>

#include "mirror.hpp"

namespace geotandem::attributes::detail {
namespace {

// A ring of the last `size` planes of a stage, each of `count` samples; slot(p) holds plane p.
class PlaneRing {
public:
  PlaneRing(int size, std::size_t count) : size_(size), count_(count), data_(static_cast<std::size_t>(size) * count) {}
  float* slot(std::int64_t p) { return data_.data() + static_cast<std::size_t>(p % size_) * count_; }
  // Pointers to planes first .. first + size - 1, in order.
  void window(std::int64_t first, std::vector<const float*>& out) {
    out.resize(static_cast<std::size_t>(size_));
    for (int t = 0; t < size_; ++t)
      out[static_cast<std::size_t>(t)] = slot(first + t);
  }

private:
  int size_;
  std::size_t count_;
  std::vector<float> data_;
};

} // namespace

void stream_structure_tensor(const volume::Volume& input, const volume::Box& box, const TensorFilters& f,
                             const std::function<void(std::int64_t, const TensorPlane&)>& plane) {
  const int rg = f.smooth.radius(), ra = f.across.radius();
  const Array3 u = read_mirrored(input, box, f.halo);
  const std::int64_t n1 = box.size(1), n2 = box.size(2);
  // Plane sizes: gradient planes are the box grown by the smoothing radii on axes 1 and 2.
  const std::int64_t g1 = n1 + 2 * ra, g2 = n2 + 2 * f.along.radius();
  const auto grad_count = static_cast<std::size_t>(g1 * g2), out_count = static_cast<std::size_t>(n1 * n2);
  const std::int64_t input_planes = u.shape[0]; // n0 + 2 (rg + ra)

  // Stage 1 (per input plane): smoothed/derived along axes 2 then 1: aa, ab, ba.
  PlaneRing partial[3] = {{2 * rg + 1, grad_count}, {2 * rg + 1, grad_count}, {2 * rg + 1, grad_count}};
  // Stage 2 (per gradient plane): the 6 products smoothed along axes 2 then 1.
  PlaneRing smoothed[6] = {{2 * ra + 1, out_count}, {2 * ra + 1, out_count}, {2 * ra + 1, out_count},
                           {2 * ra + 1, out_count}, {2 * ra + 1, out_count}, {2 * ra + 1, out_count}};
  static constexpr int pairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};

  // Stage-1 planes after the filter along the trace: u's rows, g2 samples each.
  Array3 a({1, u.shape[1], g2}), b({1, u.shape[1], g2}), product({1, g1, g2}), along_k({1, g1, n2});
  std::vector<float> grad[3], tensor[6];
  for (auto& g : grad)
    g.resize(grad_count);
  for (auto& t : tensor)
    t.resize(out_count);
  std::vector<const float*> window;
  TensorPlane result{};
  for (int c = 0; c < 6; ++c)
    result[static_cast<std::size_t>(c)] = tensor[c].data();

  const volume::Index3 plane_shape{1, u.shape[1], u.shape[2]};
  const std::size_t plane_count = static_cast<std::size_t>(u.shape[1] * u.shape[2]);
  for (std::int64_t p = 0; p < input_planes; ++p) {
    const float* up = u.data.get() + static_cast<std::size_t>(p) * plane_count;
    a.shape = correlate(up, plane_shape, 2, f.smooth, a.data.get());
    b.shape = correlate(up, plane_shape, 2, f.derive, b.data.get());
    correlate(a.data.get(), a.shape, 1, f.smooth, partial[0].slot(p));
    correlate(a.data.get(), a.shape, 1, f.derive, partial[1].slot(p));
    correlate(b.data.get(), b.shape, 1, f.smooth, partial[2].slot(p));
    if (p < 2 * rg) continue;

    // Gradient plane q = p - 2 rg: across axis 0, derivative for component 0.
    const std::int64_t q = p - 2 * rg;
    partial[0].window(q, window);
    correlate_planes(window.data(), f.derive, grad[0].data(), grad_count);
    partial[1].window(q, window);
    correlate_planes(window.data(), f.smooth, grad[1].data(), grad_count);
    partial[2].window(q, window);
    correlate_planes(window.data(), f.smooth, grad[2].data(), grad_count);
    for (int c = 0; c < 6; ++c) {
      const float* x = grad[pairs[c][0]].data();
      const float* y = grad[pairs[c][1]].data();
      float* pr = product.data.get();
      for (std::size_t n = 0; n < grad_count; ++n)
        pr[n] = x[n] * y[n];
      correlate(product.data.get(), product.shape, 2, f.along, along_k.data.get());
      correlate(along_k.data.get(), along_k.shape, 1, f.across, smoothed[c].slot(q));
    }
    if (q < 2 * ra) continue;

    // Output plane o = q - 2 ra: tensor smoothing across axis 0.
    const std::int64_t o = q - 2 * ra;
    for (int c = 0; c < 6; ++c) {
      smoothed[c].window(o, window);
      correlate_planes(window.data(), f.across, tensor[c].data(), out_count);
    }
    plane(o, result);
  }
}

} // namespace geotandem::attributes::detail
