#pragma once
// Triangle soups and what bench_flying_edges_meshopt measures on them: distances between two
// surfaces by dense sampling against a uniform grid of triangles, triangle shape (anisotropy) and
// edges shared by more than two triangles. Written for the bench, independently of geotandem's
// mesh library, so that it can judge geotandem's output and VTK's alike.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace geotandem::bench {

// Positions (x, y, z per vertex, in voxels) and triangles (three vertex indices each).
struct Surface {
  std::vector<float> xyz;
  std::vector<std::uint32_t> corners;
  std::size_t vertices() const { return xyz.size() / 3; }
  std::size_t triangles() const { return corners.size() / 3; }
};

// Distances from points sampled on one surface to the triangles of another, in voxels.
struct Distance {
  double max = 0.0;            // the largest sampled distance (a one-sided Hausdorff distance)
  double where[3] = {0, 0, 0}; // the sample it was found at
  double weighted_sum = 0.0;   // sum of distance x area over the samples of the mean
  double area = 0.0;           // the area those samples stand for
  double area_beyond = 0.0;    // the part of it whose samples are farther than the `beyond` asked for
  std::size_t samples = 0;
  double mean() const { return area > 0.0 ? weighted_sum / area : 0.0; }
};

// The triangles of a surface binned in cubic cells of `cell` voxels, for nearest-point queries.
// Keeps a reference to the surface, which must outlive it and not change.
class TriangleGrid {
public:
  TriangleGrid(const Surface& surface, double cell);
  // Exact distance from p to the nearest triangle (infinity when the surface has none).
  double distance(const double p[3]) const;

private:
  double point_triangle(const double p[3], std::uint32_t t) const;

  const Surface& surface_;
  double cell_;
  double lo_[3] = {0, 0, 0};
  std::int64_t dims_[3] = {1, 1, 1};
  std::vector<std::uint32_t> start_; // per cell, into triangles_ (CSR)
  std::vector<std::uint32_t> triangles_;
  mutable std::vector<std::uint32_t> stamp_; // per triangle: the last query that tested it
  mutable std::uint32_t query_ = 0;
};

// An axis-aligned box, closed.
struct Box {
  double lo[3] = {0, 0, 0};
  double hi[3] = {0, 0, 0};
  bool contains(const double p[3]) const {
    return p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1] && p[2] >= lo[2] && p[2] <= hi[2];
  }
};

// Distances of all samples, and of those inside a box on their own.
struct Sampled {
  Distance all;
  Distance inside;
};

// Samples `from` densely: on every triangle a barycentric grid of m x m sub-triangles with
// m = ceil(longest edge / spacing), their corners for the maximum and their centroids (each standing
// for a sub-triangle's area) for the area-weighted mean. The maximum is a sampled one: it can miss
// a peak by at most about the spacing times the slope of the distance (1). The samples in `inside`
// are also counted apart (the bench leaves out the rims of the open surfaces on the cube's faces).
// `area_beyond` sums the area of the centroid samples farther than `beyond`.
Sampled sampled_distance(const Surface& from, const TriangleGrid& to, double spacing, const Box& inside, double beyond);

// 1 - mean over triangles of sqrt(lambda2 / lambda1), the eigenvalues of the triangle's inertia
// matrix 1/3 sum (v - g)(v - g)^T (the seed's section 4): 0 when every triangle is equilateral.
double anisotropy(const Surface& surface);

// Edges (by vertex index) used by one triangle (border) and by more than two (non-manifold), and
// triangles with two equal corners.
struct EdgeCounts {
  std::size_t border = 0;
  std::size_t non_manifold = 0;
  std::size_t degenerate_triangles = 0;
};
EdgeCounts count_edges(const Surface& surface);

} // namespace geotandem::bench
