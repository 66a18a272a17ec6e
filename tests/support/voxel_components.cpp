#include "voxel_components.hpp"

#include <stdexcept>

namespace geotandem::testing {

std::array<double, 3> VoxelComponent::centroid() const {
  const double n = static_cast<double>(voxels);
  return {sum[0] / n, sum[1] / n, sum[2] / n};
}

std::array<double, 6> VoxelComponent::covariance() const {
  const auto c = centroid();
  const double n = static_cast<double>(voxels);
  return {sum2[0] / n - c[0] * c[0], sum2[1] / n - c[0] * c[1], sum2[2] / n - c[0] * c[2],
          sum2[3] / n - c[1] * c[1], sum2[4] / n - c[1] * c[2], sum2[5] / n - c[2] * c[2]};
}

bool VoxelComponent::touches_border(const std::array<std::int64_t, 3>& shape) const {
  for (int a = 0; a < 3; ++a)
    if (lo[a] == 0 || hi[a] == shape[a] - 1) return true;
  return false;
}

std::vector<VoxelComponent> voxel_components(std::span<const float> values, const std::array<std::int64_t, 3>& shape,
                                             float iso, std::vector<std::int32_t>* labels) {
  const std::int64_t ni = shape[0], nj = shape[1], nk = shape[2];
  const auto total = static_cast<std::size_t>(ni * nj * nk);
  if (values.size() != total) throw std::invalid_argument("voxel_components: values do not match the shape");
  std::vector<std::int32_t> label(total, -1);
  std::vector<VoxelComponent> components;
  std::vector<std::size_t> stack;
  for (std::size_t seed = 0; seed < total; ++seed) {
    if (!(values[seed] >= iso) || label[seed] >= 0) continue;
    const auto id = static_cast<std::int32_t>(components.size());
    VoxelComponent c;
    c.lo = {ni, nj, nk};
    c.hi = {-1, -1, -1};
    label[seed] = id;
    stack.push_back(seed);
    while (!stack.empty()) {
      const std::size_t at = stack.back();
      stack.pop_back();
      const auto n = static_cast<std::int64_t>(at);
      const std::int64_t p[3] = {n / (nj * nk), (n / nk) % nj, n % nk};
      ++c.voxels;
      for (int a = 0; a < 3; ++a) {
        c.lo[a] = std::min(c.lo[a], p[a]);
        c.hi[a] = std::max(c.hi[a], p[a]);
        c.sum[a] += static_cast<double>(p[a]);
      }
      const double x = static_cast<double>(p[0]), y = static_cast<double>(p[1]), z = static_cast<double>(p[2]);
      c.sum2[0] += x * x;
      c.sum2[1] += x * y;
      c.sum2[2] += x * z;
      c.sum2[3] += y * y;
      c.sum2[4] += y * z;
      c.sum2[5] += z * z;
      const std::int64_t steps[3] = {nj * nk, nk, 1};
      for (int a = 0; a < 3; ++a)
        for (int side : {-1, 1}) {
          const std::int64_t q = p[a] + side;
          if (q < 0 || q >= shape[a]) continue;
          const auto next = static_cast<std::size_t>(n + side * steps[a]);
          if (values[next] >= iso && label[next] < 0) {
            label[next] = id;
            stack.push_back(next);
          }
        }
    }
    components.push_back(c);
  }
  if (labels) *labels = std::move(label);
  return components;
}

} // namespace geotandem::testing
