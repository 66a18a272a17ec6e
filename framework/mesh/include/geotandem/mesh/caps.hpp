#pragma once
// Caps: the triangles that close a body cut by the cube's border. They lie on the cube's outer
// sample planes (index 0 or n - 1 along an axis) and face out of the cube (docs/caps.md).

#include <cstdint>
#include <string>

#include "geotandem/mesh/surface.hpp"
#include "geotandem/volume/geometry.hpp"

namespace geotandem::mesh {

// Bits 2 * axis + side of the outer planes a point (index coordinates) lies on.
std::uint8_t outer_planes(const Point& p, const volume::Index3& shape);

// The cut-face bit of a cap triangle (all corners on one outer plane, normal out of the cube),
// or -1 when the triangle is not a cap.
int cap_face(const SurfaceMesh& index_surface, const Triangle& t, const volume::Index3& shape);

// The surface without its caps (the open surface the isovalue makes), points no triangle uses
// left out. The first takes index coordinates, the second world coordinates (as stored; the cube's
// planes are found through the inverse of the geometry's affine).
SurfaceMesh without_caps(const SurfaceMesh& index_surface, const volume::Index3& shape);
SurfaceMesh without_world_caps(const SurfaceMesh& world_surface, const volume::Geometry& geometry);

} // namespace geotandem::mesh
