#pragma once
// An independent oracle for isosurface extraction: the 6-connected components of the samples at or
// above an iso value in a C-order [i][j][k] array (k fastest), with their size, bounding box and
// moments. Plain flood fill, no cleverness, so that it can be trusted.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace geotandem::testing {

struct VoxelComponent {
  std::size_t voxels = 0;
  std::array<std::int64_t, 3> lo{}; // inclusive sample bounds
  std::array<std::int64_t, 3> hi{}; // inclusive
  std::array<double, 3> sum{};      // sum of i, j, k over the voxels
  // Sum of products ii, ij, ik, jj, jk, kk (for centroids and principal axes).
  std::array<double, 6> sum2{};

  std::array<double, 3> centroid() const;
  // Covariance (population) of i, j, k in the order ii, ij, ik, jj, jk, kk.
  std::array<double, 6> covariance() const;
  bool touches_border(const std::array<std::int64_t, 3>& shape) const;
};

// Components of {values >= iso}; `values` holds shape[0]*shape[1]*shape[2] samples. When `labels`
// is given it receives, per sample, the component's index or -1.
std::vector<VoxelComponent> voxel_components(std::span<const float> values, const std::array<std::int64_t, 3>& shape,
                                             float iso, std::vector<std::int32_t>* labels = nullptr);

} // namespace geotandem::testing
