#pragma once
// Surfaces built from formulas for tests: closed bodies oriented outward (counter-clockwise seen
// from outside) by construction, plus deliberately broken ones. Any test may link
// geotandem_mesh_fixtures and use them.

#include <array>
#include <cstdint>

#include "geotandem/mesh/surface.hpp"

namespace geotandem::mesh::fixtures {

// Icosahedron refined `level` times by edge midpoints, projected on the sphere. 20 * 4^level
// triangles, 10 * 4^level + 2 vertices.
SurfaceMesh icosphere(int level, double radius = 1.0, const Point& center = {0.0, 0.0, 0.0});

// Torus around the z axis: tube radius r around a circle of radius R; nu segments around z, nv
// around the tube. 2 * nu * nv triangles. Enclosed volume 2 pi^2 R r^2 in the limit.
SurfaceMesh torus(double R, double r, int nu, int nv);

// Axis-aligned box [lo, hi], 8 vertices and 12 triangles.
SurfaceMesh box(const Point& lo, const Point& hi);

// Regular tetrahedron-like body with the given four corners, oriented outward.
SurfaceMesh tetrahedron(const Point& a, const Point& b, const Point& c, const Point& d);

// Flat disc in the plane z = height, centred at the origin, normal +z: `rings` rings of
// `segments` triangles fanned around the centre. Open: `segments` boundary edges.
SurfaceMesh disc(double radius, int rings, int segments, double height = 0.0);

// Open hemisphere z >= 0 of the sphere of radius r (latitude-longitude grid, pole at +z),
// normals outward. Its boundary is the equator (z = 0).
SurfaceMesh hemisphere(double radius, int stacks, int slices);

// Appends `b` to `a` with b's indices shifted (two bodies in one surface, no shared vertex).
SurfaceMesh merged(const SurfaceMesh& a, const SurfaceMesh& b);

// p -> center + R * diag(scale) * p with R a rotation: `azimuth_deg` clockwise from north (+y)
// about the vertical, after `dip_deg` tilting the +y axis down towards +z (z down). The body's
// local +y axis ends up pointing to (sin az cos dip, cos az cos dip, sin dip).
SurfaceMesh transformed(const SurfaceMesh& s, const Point& scale, double azimuth_deg, double dip_deg,
                        const Point& center);

// Every triangle gets its own three vertices; keys[v] is the original vertex index.
struct Unwelded {
  SurfaceMesh surface;
  std::vector<std::uint64_t> keys;
};
Unwelded unwelded(const SurfaceMesh& s);

} // namespace geotandem::mesh::fixtures
