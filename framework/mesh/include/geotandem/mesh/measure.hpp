#pragma once
// Measuring a component for the store's index (design section 7): counts, enclosed volume, area,
// centroid, boxes, principal axes, azimuth, dip, elongation, closed or cut by the border.

#include <vector>

#include "geotandem/mesh/component.hpp"
#include "geotandem/volume/geometry.hpp"

namespace geotandem::mesh {

// Maps a surface from index coordinates (i, j, k) to world coordinates (x east, y north, z down in
// the sample unit) through the geometry's survey affine. Triangle orientation is flipped when the
// map reverses handedness (the sign of (xi*yj - xj*yi) * dz), so outward normals stay outward and
// enclosed volumes stay positive. Throws InvalidArgument when that determinant is 0 or not finite.
SurfaceMesh to_world(const SurfaceMesh& index_surface, const volume::Geometry& geometry);

// Measures a component given in index coordinates. World measures go through `geometry`; the
// cube's border is geometry.bounds() (a boundary edge lying on an outer sample plane marks the
// component as cut by the border). Throws InvalidArgument on an empty surface, an invalid geometry
// or an out-of-range vertex index. Definitions (docs/measures.md): area-weighted moments of the
// surface as a uniform sheet; the azimuth and elongation come from the (x, y) block of its
// covariance, the dip from its main 3-D axis. The dip mixes metres with the sample unit, so it is
// an angle only for depth cubes; for time cubes it depends on dz and is only comparable between
// bodies of the same cube.
ComponentStats measure_component(const SurfaceMesh& index_surface, const volume::Geometry& geometry);

// Axial mean of azimuths in degrees by angle doubling: 1/2 atan2(sum sin 2t, sum cos 2t), in
// [0, 180); weights optional (empty = equal). Returns 0 when the doubled angles cancel (no list,
// or {0, 90}). Throws InvalidArgument when weights are given but not one per azimuth.
double axial_mean_deg(const std::vector<double>& azimuths_deg, const std::vector<double>& weights = {});

// Smallest difference between two axial angles in degrees, in [0, 90].
double axial_difference_deg(double a, double b);

} // namespace geotandem::mesh
