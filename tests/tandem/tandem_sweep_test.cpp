// The sweep as a whole: components leave memory as soon as they are finished, the triangles held
// per layer are recorded, brute force gives the same bodies with far more memory, garbage
// collection keeps everything consistent, cancellation stops the loop.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/quality.hpp"
#include "geotandem/mesh/topology.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "simplify_fixtures.hpp"

namespace geotandem::tandem {
namespace {

using fixtures::CollectingSink;
using fixtures::Field;

// Three balls stacked along k, far apart.
const volume::Index3 kShape{24, 25, 90};
Field three_balls() {
  return fixtures::union_of({fixtures::sphere({11.6, 12.3, 15.4}, 5.5), fixtures::sphere({12.2, 11.7, 45.1}, 6.2),
                             fixtures::sphere({11.9, 12.1, 74.8}, 5.1)});
}

struct Sweep {
  CollectingSink sink;
  TandemStats stats;
};

void sweep(Sweep& s, const fixtures::Input& input, bool dump, bool brute = false) {
  const volume::Box cells = input.cells();
  const auto source = input.layers(cells, 2);
  TandemOptions options;
  options.axis = 2;
  options.dump = dump;
  options.simplify.compaction_min_dead = 1000; // compact often: these inputs are small
  WorkingSurface surface(fixtures::test_geometry(input.shape()), Region::block(cells, cells), 2, options.simplify,
                         &s.sink);
  s.sink.surface = &surface;
  s.stats = brute ? run_brute(*source, surface, options) : run_tandem(*source, surface, options);
}

TEST(TandemSweep, FinishedComponentsLeaveMemoryDuringTheSweep) {
  Sweep s;
  sweep(s, fixtures::Input(three_balls(), kShape), true);
  ASSERT_EQ(s.sink.components.size(), 3u);
  // Each ball is dumped shortly after the front has passed it (time lag: a few layers), long
  // before the end of the cube.
  std::vector<std::int64_t> fronts = s.sink.commit_front;
  EXPECT_LT(fronts[0], 15 + 6 + 12);
  EXPECT_LT(fronts[1], 45 + 7 + 12);
  EXPECT_LT(fronts[2], 89);
  for (const mesh::Component& c : s.sink.components) {
    EXPECT_TRUE(mesh::check_topology(c.surface).is_closed_manifold());
    EXPECT_TRUE(c.stats.closed);
  }
  std::set<std::uint64_t> keys;
  for (const mesh::Component& c : s.sink.components)
    keys.insert(c.key);
  EXPECT_EQ(keys.size(), 3u);
  // Between the balls nothing is held; while a ball is being swept something is.
  ASSERT_EQ(s.stats.layers.size(), 89u);
  const auto held = [&](std::int64_t rank) {
    return s.stats.layers[static_cast<std::size_t>(rank - 1)].triangles_in_memory;
  };
  EXPECT_GT(held(15), 0u);
  EXPECT_EQ(held(35), 0u);
  EXPECT_GT(held(45), 0u);
  EXPECT_EQ(held(62), 0u);
  EXPECT_EQ(s.stats.remaining_triangles, 0u);
  std::uint64_t dumped = 0;
  for (const LayerStats& l : s.stats.layers)
    dumped += l.components_dumped;
  EXPECT_EQ(dumped + s.stats.final_pass.components_dumped, 3u);
  EXPECT_GE(dumped, 2u); // at least the first two during the sweep
}

TEST(TandemSweep, WithoutDumpingEverythingWaitsForTheEnd) {
  Sweep on, off;
  const fixtures::Input input(three_balls(), kShape);
  sweep(on, input, true);
  sweep(off, input, false);
  ASSERT_EQ(off.sink.components.size(), 3u);
  for (std::int64_t f : off.sink.commit_front)
    EXPECT_GT(f, 89); // committed after activate(inf)
  // Same bodies: the dumping changes when they leave, not what they are.
  std::vector<double> v_on, v_off;
  for (const auto& c : on.sink.components)
    v_on.push_back(mesh::enclosed_volume(c.surface));
  for (const auto& c : off.sink.components)
    v_off.push_back(mesh::enclosed_volume(c.surface));
  std::sort(v_on.begin(), v_on.end());
  std::sort(v_off.begin(), v_off.end());
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(v_on[i], v_off[i], 1e-9 * v_on[i]);
  // The plain tandem holds the simplified balls until the end.
  EXPECT_GT(off.stats.layers.back().triangles_in_memory, 0u);
  EXPECT_GT(off.stats.layers[61].triangles_in_memory, on.stats.layers[61].triangles_in_memory);
  EXPECT_GE(off.stats.peak_triangles, on.stats.peak_triangles);
}

TEST(TandemSweep, BruteForceFindsTheSameBodiesWithAllTrianglesInMemory) {
  Sweep tandem, brute;
  const fixtures::Input input(three_balls(), kShape);
  sweep(tandem, input, true);
  sweep(brute, input, true, true);
  ASSERT_EQ(brute.sink.components.size(), 3u);
  std::uint64_t triangles = 0;
  for (const LayerStats& l : brute.stats.layers) {
    triangles += l.input_triangles;
    EXPECT_EQ(l.triangles_in_memory, triangles); // nothing is simplified before the end
    EXPECT_EQ(l.collapses, 0u);
  }
  EXPECT_EQ(brute.stats.peak_triangles, triangles);
  EXPECT_LT(tandem.stats.peak_triangles * 4, brute.stats.peak_triangles);
  std::vector<double> vt, vb;
  for (const auto& c : tandem.sink.components)
    vt.push_back(mesh::enclosed_volume(c.surface));
  for (const auto& c : brute.sink.components) {
    vb.push_back(mesh::enclosed_volume(c.surface));
    EXPECT_TRUE(mesh::check_topology(c.surface).is_closed_manifold());
  }
  std::sort(vt.begin(), vt.end());
  std::sort(vb.begin(), vb.end());
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(vt[i] / vb[i], 1.0, 0.01);
}

TEST(TandemSweep, ManyBubblesAreDumpedAndCompactionKeepsTheRestConsistent) {
  // A lattice of small bubbles: hundreds of components, most of the mesh storage dies, garbage
  // collection runs during the sweep; a large body crossing the whole sweep must survive it.
  std::vector<Field> bodies;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 14; ++k)
        bodies.push_back(fixtures::sphere({3.2 + 4.0 * i, 3.1 + 4.0 * j, 3.3 + 4.0 * k}, 1.4));
  bodies.push_back(fixtures::ellipsoid({26.0, 12.0, 30.0}, {3.5, 3.5, 26.0}));
  const volume::Index3 shape{32, 24, 60};
  const fixtures::Input input(fixtures::union_of(bodies), shape);
  const mesh::SurfaceMesh full = input.full(input.cells(), 2);
  const std::size_t expected = mesh::split_components(full).size();
  Sweep s;
  sweep(s, input, true);
  EXPECT_GT(s.stats.counters.garbage_collections, 0u);
  EXPECT_EQ(s.sink.components.size(), expected);
  std::set<std::uint64_t> keys;
  double total = 0.0;
  for (const mesh::Component& c : s.sink.components) {
    keys.insert(c.key);
    const mesh::TopologyReport t = mesh::check_topology(c.surface);
    ASSERT_TRUE(t.is_closed_manifold()) << t.summary();
    ASSERT_EQ(t.components, 1u);
    total += mesh::enclosed_volume(c.surface);
  }
  EXPECT_EQ(keys.size(), expected);
  EXPECT_NEAR(total / mesh::enclosed_volume(full), 1.0, 0.02);
}

TEST(TandemSweep, CancellationStopsTheLoop) {
  CancelToken token;
  token.cancel();
  Sweep s;
  const volume::Box cells = cube_cells(kShape);
  const fixtures::Input input(three_balls(), kShape);
  const auto source = input.layers(cells, 2);
  TandemOptions options;
  options.axis = 2;
  options.cancel = &token;
  WorkingSurface surface(fixtures::test_geometry(kShape), Region::block(cells, cells), 2, options.simplify, &s.sink);
  EXPECT_THROW(run_tandem(*source, surface, options), Cancelled);
}

} // namespace
} // namespace geotandem::tandem
