#pragma once
// Shared by the block and wire-format tests: a cube of several bodies that cross the block planes
// of the trees used, sampled into a volume, and comparisons of two sets of components.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "geotandem/mesh/quality.hpp"
#include "geotandem/mesh/topology.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "simplify_fixtures.hpp"

namespace geotandem::tandem::blocks_test {

// 65 x 49 x 49 samples: 64 x 48 x 48 cells. Leaf sizes 64, 48, 32 and 16 give 1, 2, 8 and 64
// blocks, cut at i = 32; then j = 24 and k = 24; then i = 16, 48, j = 12, 36, k = 12, 36.
inline const volume::Index3 kShape{65, 49, 49};

// Six bodies, all inside the cube (none touches its faces), five crossing block planes: a large
// ellipsoid across the centre, a smaller one, a ball, a torus (genus 1), a long thin ellipsoid
// crossing three i-planes, and a small ball inside one leaf of the 64-block tree; with the bumps,
// a seventh, a small bubble broken off the big ellipsoid.
inline fixtures::Field bodies() {
  using namespace fixtures;
  // Bumps of about a voxel, a few voxels apart, so that the simplified bodies keep enough triangles
  // for their quality measures to be statistics.
  const Field smooth =
      union_of({ellipsoid({32.3, 24.4, 23.7}, {12.0, 8.0, 7.0}), ellipsoid({14.6, 11.2, 36.5}, {6.5, 5.0, 8.0}),
                sphere({49.2, 37.4, 10.3}, 7.0), torus({47.5, 14.5, 34.5}, 7.0, 2.5),
                ellipsoid({30.5, 38.2, 40.1}, {20.0, 3.0, 3.0}), sphere({24.2, 30.1, 6.3}, 3.0)});
  return [smooth](double i, double j, double k) {
    return smooth(i, j, k) + 0.6 * std::sin(1.1 * i + 0.3) * std::sin(0.9 * j + 1.2) * std::sin(1.3 * k + 0.7);
  };
}
inline constexpr std::size_t kBodies = 7;
// E0 of the comparisons: small enough for the bodies to keep hundreds of triangles each.
inline constexpr double kMaxError = 0.1;

inline std::unique_ptr<volume::MemoryVolume> sample(const fixtures::Field& field, const volume::Index3& shape) {
  const volume::Geometry g = fixtures::test_geometry(shape);
  std::vector<float> samples(g.bounds().count());
  for (std::int64_t i = 0; i < shape[0]; ++i)
    for (std::int64_t j = 0; j < shape[1]; ++j)
      for (std::int64_t k = 0; k < shape[2]; ++k)
        samples[g.bounds().offset({i, j, k})] =
            static_cast<float>(field(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k)));
  return std::make_unique<volume::MemoryVolume>(g, std::move(samples), "bodies across block planes");
}

inline std::vector<mesh::Component> by_key(std::vector<mesh::Component> components) {
  std::sort(components.begin(), components.end(),
            [](const mesh::Component& a, const mesh::Component& b) { return a.key < b.key; });
  return components;
}

// The same components: same keys, every one a closed 2-manifold of the same Euler characteristic,
// volumes within `volume_tolerance` (relative), the anisotropy of all triangles together within
// `anisotropy_tolerance`, and that of each component of at least 100 triangles within
// `component_anisotropy_tolerance` (a body of a few hundred triangles changes its anisotropy by a
// few hundredths with the order of its collapses alone: the tandem and the brute force differ by
// up to 0.1 on one block).
inline void expect_same_components(const std::vector<mesh::Component>& reference,
                                   const std::vector<mesh::Component>& other, double volume_tolerance = 0.005,
                                   double anisotropy_tolerance = 0.02, double component_anisotropy_tolerance = 0.03) {
  const auto a = by_key(reference), b = by_key(other);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_NEAR(mesh::anisotropy(fixtures::concatenate(b)), mesh::anisotropy(fixtures::concatenate(a)),
              anisotropy_tolerance);
  for (std::size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE("component " + std::to_string(a[i].key));
    EXPECT_EQ(a[i].key, b[i].key);
    const mesh::TopologyReport t = mesh::check_topology(b[i].surface);
    EXPECT_TRUE(t.is_closed_manifold()) << t.summary();
    EXPECT_EQ(t.degenerate_triangles, 0u) << t.summary();
    EXPECT_EQ(t.euler_characteristic, mesh::check_topology(a[i].surface).euler_characteristic);
    const double va = mesh::enclosed_volume(a[i].surface), vb = mesh::enclosed_volume(b[i].surface);
    EXPECT_NEAR(vb / va, 1.0, volume_tolerance) << "volumes " << va << " and " << vb;
    if (a[i].surface.triangle_count() >= 100) {
      EXPECT_NEAR(mesh::anisotropy(b[i].surface), mesh::anisotropy(a[i].surface), component_anisotropy_tolerance);
    }
  }
}

} // namespace geotandem::tandem::blocks_test
