#pragma once
// Components from formulas for the store's tests: rotated ellipsoids (icosphere-based) at known
// positions of a small cube with a rotated survey, with deterministic, varied measures.

#include <cstdint>

#include "geotandem/mesh/component.hpp"
#include "geotandem/volume/geometry.hpp"

namespace geotandem::store::testing {

// 60 x 50 x 40 cube, 25 m bins rotated 20 degrees from north, 4 ms samples.
volume::Geometry test_geometry();

// Unit icosphere: 12 vertices at level 0, each level splits every triangle in four.
mesh::SurfaceMesh icosphere(int level);

// The component of `key`: an ellipsoid (index coordinates) whose position, semi-axes, rotation and
// icosphere level (0 to max_level) follow from the key. Its stats are plausible world measures:
// the bounding box and centroid of its world surface, the volume 4/3 pi abc scaled to world
// units, and an azimuth, dip and flags drawn from the key. Same key, same component.
mesh::Component make_component(std::uint64_t key, const volume::Geometry& geometry, int max_level = 1);

bool same_surface(const mesh::SurfaceMesh& a, const mesh::SurfaceMesh& b);
bool same_stats(const mesh::ComponentStats& a, const mesh::ComponentStats& b);

} // namespace geotandem::store::testing
