#pragma once
// Mesh quality and distance measures (section 4 of the seed; ALGORITHM.md "Quality"). Functions
// taking a surface throw InvalidArgument when a triangle refers to a vertex that does not exist.

#include "geotandem/mesh/surface.hpp"

namespace geotandem::mesh {

// rho(t) = sqrt(lambda2 / lambda1) of the triangle's inertia matrix
// M_t = 1/3 sum over corners (v - t^)(v - t^)^T; 1 for equilateral, 0 flat (and for a point).
double aspect_ratio(const Point& a, const Point& b, const Point& c);
// 1 - mean rho over triangles; 0 when every triangle is equilateral. 0 for an empty surface.
double anisotropy(const SurfaceMesh& surface);
// Share of triangles whose smallest angle is below `degrees` (default 10), in [0, 1]; 0 for an
// empty surface. A triangle with a zero-length edge has a zero angle.
double small_angle_share(const SurfaceMesh& surface, double degrees = 10.0);
// Total area and enclosed volume (divergence theorem; meaningful for closed, outward surfaces), in
// the units of the coordinates (squared, cubed).
double surface_area(const SurfaceMesh& surface);
double enclosed_volume(const SurfaceMesh& surface);

struct DistanceStats {
  double max = 0.0; // one-sided Hausdorff distance
  double rms = 0.0;
  double mean = 0.0;
  std::size_t samples = 0;
};

// Distances from points sampled on `from` (its vertices plus `samples_per_triangle` barycentric
// samples per triangle) to the nearest point of the triangles of `to`. Uses a uniform grid over
// `to`; fine for millions of triangles. Distances are exact point-to-triangle distances in the
// units of the coordinates. The vertices sampled are those the triangles of `from` use. An empty
// `from` gives zero samples. Throws InvalidArgument when `to` has no triangles but `from` has, or
// when samples_per_triangle is negative; throws DataError on a non-finite coordinate.
DistanceStats one_sided_distance(const SurfaceMesh& from, const SurfaceMesh& to, int samples_per_triangle = 3);
// max of both directions for max, and the pooled rms/mean.
DistanceStats hausdorff_distance(const SurfaceMesh& a, const SurfaceMesh& b, int samples_per_triangle = 3);

} // namespace geotandem::mesh
