// Degenerate and malformed inputs: single-triangle layers, empty cubes, tiny bubbles, bodies cut by
// the cube's border, and layers that break the contract.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/quality.hpp"
#include "geotandem/mesh/topology.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "simplify_fixtures.hpp"

namespace geotandem::tandem {
namespace {

using fixtures::CollectingSink;

const volume::Index3 kShape{12, 12, 12};

WorkingSurface make_surface(CollectingSink& sink, int axis = 2, SimplifyOptions options = {}) {
  const volume::Box cells = cube_cells(kShape);
  return WorkingSurface(fixtures::test_geometry(kShape), Region::block(cells, cells), axis, options, &sink);
}

Layer layer(std::int64_t rank, std::vector<std::uint64_t> ids, std::vector<std::array<double, 3>> positions,
            std::vector<std::array<std::uint32_t, 3>> triangles) {
  Layer l;
  l.axis = 2;
  l.rank = rank;
  l.vertex_ids = std::move(ids);
  l.positions = std::move(positions);
  l.triangles = std::move(triangles);
  return l;
}

TEST(TandemInputs, SingleTriangleLayerBecomesOneOpenComponent) {
  CollectingSink sink;
  WorkingSurface surface = make_surface(sink);
  surface.add_layer(layer(3, {30, 60, 90}, {{4, 4, 2.5}, {5, 4, 2.5}, {4.5, 5, 2.2}}, {{0, 1, 2}}));
  surface.activate(3);
  surface.simplify();
  EXPECT_EQ(surface.dump(), 0u) << "its edges wait behind the front";
  surface.finish();
  ASSERT_EQ(sink.components.size(), 1u);
  EXPECT_EQ(sink.components[0].surface.triangle_count(), 1u);
  EXPECT_EQ(sink.components[0].key, 30u);
  EXPECT_FALSE(sink.components[0].stats.closed);
  EXPECT_EQ(surface.triangle_count(), 0u);
}

TEST(TandemInputs, RibbonOfTwoTrianglesPerLayerStaysAManifold) {
  // A flat ribbon x in [4, 5], y = 6, one quad per layer, welded through repeated ids.
  CollectingSink sink;
  WorkingSurface surface = make_surface(sink);
  auto id = [](int side, int k) { return static_cast<std::uint64_t>(100 + 2 * k + side); };
  for (int k = 1; k <= 10; ++k) {
    surface.add_layer(layer(k, {id(0, k - 1), id(1, k - 1), id(0, k), id(1, k)},
                            {{4, 6, k - 1.0}, {5, 6, k - 1.0}, {4, 6, k * 1.0}, {5, 6, k * 1.0}},
                            {{0, 1, 3}, {0, 3, 2}}));
    surface.activate(k);
    surface.simplify();
    surface.dump();
  }
  surface.finish();
  ASSERT_EQ(sink.components.size(), 1u);
  const mesh::TopologyReport t = mesh::check_topology(sink.components[0].surface);
  EXPECT_TRUE(t.is_manifold()) << t.summary();
  EXPECT_EQ(t.misoriented_edges, 0u);
  EXPECT_EQ(t.euler_characteristic, 1); // a disc
  EXPECT_LT(sink.components[0].surface.triangle_count(), 20u);
  for (const auto& p : sink.components[0].surface.points)
    EXPECT_NEAR(p[1], 6.0, 1e-9);
}

TEST(TandemInputs, EmptyCubeAndEmptyLayersAreFine) {
  CollectingSink sink;
  fixtures::TetraLayers source([](double, double, double) { return -1.0; }, kShape, cube_cells(kShape), 0.0, 2);
  WorkingSurface surface = make_surface(sink);
  const TandemStats stats = run_tandem(source, surface, {.axis = 2});
  EXPECT_EQ(stats.layers.size(), 11u);
  EXPECT_TRUE(sink.components.empty());
  EXPECT_EQ(stats.peak_triangles, 0u);
}

TEST(TandemInputs, TinyBubblesAreEachOneClosedComponent) {
  std::vector<fixtures::Field> bubbles;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) // one sample inside each: the smallest body there is
        bubbles.push_back(fixtures::sphere({2.0 + 3.0 * i, 3.0 + 3.0 * j, 2.0 + 4.0 * k}, 0.6));
  const fixtures::Field field = fixtures::union_of(bubbles);
  CollectingSink sink;
  fixtures::TetraLayers source(field, kShape, cube_cells(kShape), 0.0, 2);
  WorkingSurface surface = make_surface(sink);
  run_tandem(source, surface, {.axis = 2});
  ASSERT_EQ(sink.components.size(), 27u);
  for (const mesh::Component& c : sink.components) {
    const mesh::TopologyReport t = mesh::check_topology(c.surface);
    EXPECT_TRUE(t.is_closed_manifold()) << t.summary();
    EXPECT_EQ(t.euler_characteristic, 2);
    EXPECT_GT(mesh::enclosed_volume(c.surface), 0.0);
  }
}

TEST(TandemInputs, BodiesCutByTheBorderKeepTheirBoundaryOnTheCubeFace) {
  // A ball centred on the face i = 0: half of it is in the cube, its boundary lies on i = 0.
  const volume::Index3 shape{16, 24, 24};
  const fixtures::Field field = fixtures::sphere({0.0, 11.7, 12.2}, 8.5);
  CollectingSink sink;
  const volume::Box cells = cube_cells(shape);
  fixtures::TetraLayers source(field, shape, cells, 0.0, 2);
  WorkingSurface surface(fixtures::test_geometry(shape), Region::block(cells, cells), 2, {}, &sink);
  run_tandem(source, surface, {.axis = 2});
  ASSERT_EQ(sink.components.size(), 1u);
  const mesh::Component& c = sink.components[0];
  EXPECT_TRUE(c.stats.cut_by_border);
  EXPECT_FALSE(c.stats.closed);
  // Boundary edges (one triangle) must lie on i = 0.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const auto& t : c.surface.triangles)
    for (int e = 0; e < 3; ++e) {
      auto a = t[static_cast<std::size_t>(e)], b = t[static_cast<std::size_t>((e + 1) % 3)];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  std::size_t boundary = 0;
  for (const auto& [edge, n] : uses) {
    if (n != 1) continue;
    ++boundary;
    EXPECT_EQ(c.surface.points[edge.first][0], 0.0);
    EXPECT_EQ(c.surface.points[edge.second][0], 0.0);
  }
  EXPECT_GT(boundary, 3u);
  const mesh::SurfaceMesh full = fixtures::tetra_surface(field, shape, cells, 0.0, 2);
  EXPECT_LT(c.surface.triangle_count(), full.triangle_count() / 5);
  EXPECT_LE(mesh::hausdorff_distance(c.surface, full).max, 0.5); // the E0 guarantee
}

TEST(TandemInputs, MalformedLayersAreRefusedWithTypedErrors) {
  CollectingSink sink;
  {
    WorkingSurface s = make_surface(sink);
    EXPECT_THROW(s.add_layer(layer(1, {3, 6, 9}, {{1, 1, 1}, {2, 1, 1}, {1, 2, 1}}, {{0, 1, 3}})), DataError);
  }
  {
    WorkingSurface s = make_surface(sink);
    EXPECT_THROW(s.add_layer(layer(1, {3, 6, 9}, {{1, 1, 1}, {2, 1, 1}, {1, 2, 1}}, {{0, 1, 1}})), DataError);
  }
  {
    // Three triangles on one edge.
    WorkingSurface s = make_surface(sink);
    EXPECT_THROW(
        s.add_layer(layer(1, {3, 6, 9, 12, 15}, {{1, 1, 0.5}, {2, 1, 0.5}, {1, 2, 0.5}, {1, 0, 0.5}, {1.5, 1.5, 0.9}},
                          {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}})),
        DataError);
  }
  {
    WorkingSurface s = make_surface(sink);
    Layer wrong = layer(1, {3, 6, 9}, {{1, 1, 1}, {2, 1, 1}, {1, 2, 1}}, {{0, 1, 2}});
    wrong.axis = 0;
    EXPECT_THROW(s.add_layer(wrong), InvalidArgument);
    s.add_layer(layer(2, {3, 6, 9}, {{1, 1, 1.5}, {2, 1, 1.5}, {1, 2, 1.5}}, {{0, 1, 2}}));
    EXPECT_THROW(s.add_layer(layer(2, {12, 15, 18}, {{1, 1, 2}, {2, 1, 2}, {1, 2, 2}}, {{0, 1, 2}})), InvalidArgument);
    s.activate(2.0);
    EXPECT_THROW(s.activate(1.0), InvalidArgument);
  }
  EXPECT_THROW(WorkingSurface(fixtures::test_geometry(kShape), Region(), 2, {.max_error = 0.0}, &sink),
               InvalidArgument);
  EXPECT_THROW(WorkingSurface(fixtures::test_geometry(kShape), Region(), 2, {.isotropy = 1.5}, &sink), InvalidArgument);
  EXPECT_THROW(WorkingSurface(fixtures::test_geometry(kShape), Region(), 3, {}, &sink), InvalidArgument);
}

TEST(TandemInputs, ALayerCannotReuseAVertexTheFrontHasPassed) {
  // Layer 1 is a flat patch on cross-section 1. Without the time lag, a front at 1.5 lets it be
  // simplified; a layer 2 repeating the id of a vertex that was collapsed away is then refused.
  CollectingSink sink;
  SimplifyOptions options;
  options.time_lag = false;
  WorkingSurface s = make_surface(sink, 2, options);
  std::vector<std::uint64_t> ids;
  std::vector<std::array<double, 3>> pos;
  std::vector<std::array<std::uint32_t, 3>> tris;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      ids.push_back(static_cast<std::uint64_t>(1000 + 10 * i + j));
      pos.push_back({3.0 + i, 3.0 + j, 1.0});
    }
  for (std::uint32_t i = 0; i < 3; ++i)
    for (std::uint32_t j = 0; j < 3; ++j) {
      tris.push_back({4 * i + j, 4 * (i + 1) + j, 4 * (i + 1) + j + 1});
      tris.push_back({4 * i + j, 4 * (i + 1) + j + 1, 4 * i + j + 1});
    }
  s.add_layer(layer(1, ids, pos, tris));
  s.activate(1.5);
  s.simplify();
  ASSERT_GT(s.counters().collapses, 0u);
  const mesh::SurfaceMesh snap = s.snapshot();
  std::uint64_t gone = 0;
  for (std::size_t v = 0; v < ids.size(); ++v)
    if (std::find(snap.points.begin(), snap.points.end(), pos[v]) == snap.points.end()) gone = ids[v];
  ASSERT_NE(gone, 0u);
  EXPECT_THROW(s.add_layer(layer(2, {gone, 7, 8}, {pos[0], {5, 6, 2}, {6, 5, 2}}, {{0, 1, 2}})), DataError);
}

} // namespace
} // namespace geotandem::tandem
