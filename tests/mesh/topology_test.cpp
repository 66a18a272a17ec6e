// check_topology, split_components and weld_by_key on surfaces built from formulas, clean and
// deliberately broken.

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/quality.hpp"
#include "geotandem/mesh/topology.hpp"
#include "mesh_fixtures.hpp"

namespace geotandem::mesh {
namespace {

using namespace fixtures;

void expect_clean_closed(const TopologyReport& r) {
  EXPECT_TRUE(r.is_closed_manifold()) << r.summary();
  EXPECT_EQ(r.boundary_edges, 0u) << r.summary();
  EXPECT_EQ(r.non_manifold_edges, 0u) << r.summary();
  EXPECT_EQ(r.non_manifold_vertices, 0u) << r.summary();
  EXPECT_EQ(r.misoriented_edges, 0u) << r.summary();
  EXPECT_EQ(r.degenerate_triangles, 0u) << r.summary();
  EXPECT_EQ(r.unreferenced_vertices, 0u) << r.summary();
}

TEST(Topology, IcospheresAreClosedSpheres) {
  for (int level = 0; level <= 4; ++level) {
    const SurfaceMesh s = icosphere(level, 2.0);
    const TopologyReport r = check_topology(s);
    expect_clean_closed(r);
    EXPECT_EQ(r.euler_characteristic, 2) << r.summary();
    EXPECT_EQ(r.components, 1u);
    EXPECT_EQ(r.vertices, s.points.size());
    EXPECT_EQ(r.triangles, s.triangles.size());
  }
}

TEST(Topology, TorusHasEulerZero) {
  const TopologyReport r = check_topology(torus(3.0, 1.0, 24, 12));
  expect_clean_closed(r);
  EXPECT_EQ(r.euler_characteristic, 0) << r.summary();
  EXPECT_EQ(r.components, 1u);
}

TEST(Topology, BoxAndTetrahedronAreClosed) {
  const TopologyReport b = check_topology(box({0, 0, 0}, {3, 2, 1}));
  expect_clean_closed(b);
  EXPECT_EQ(b.euler_characteristic, 2);
  const TopologyReport t = check_topology(tetrahedron({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}));
  expect_clean_closed(t);
  EXPECT_EQ(t.euler_characteristic, 2);
}

TEST(Topology, OpenDiscHasItsRimAsBoundary) {
  const int segments = 16;
  const TopologyReport r = check_topology(disc(1.0, 4, segments));
  EXPECT_EQ(r.boundary_edges, static_cast<std::size_t>(segments)) << r.summary();
  EXPECT_TRUE(r.is_manifold()) << r.summary(); // rim vertices are half-discs, not defects
  EXPECT_FALSE(r.is_closed_manifold());
  EXPECT_EQ(r.misoriented_edges, 0u);
  EXPECT_EQ(r.euler_characteristic, 1) << r.summary();
}

TEST(Topology, FlippedTriangleGivesThreeMisorientedEdges) {
  SurfaceMesh s = icosphere(2);
  std::swap(s.triangles[17][1], s.triangles[17][2]);
  const TopologyReport r = check_topology(s);
  EXPECT_EQ(r.misoriented_edges, 3u) << r.summary();
  EXPECT_TRUE(r.is_manifold());
  EXPECT_FALSE(r.is_closed_manifold());
  EXPECT_EQ(r.boundary_edges, 0u);
  EXPECT_EQ(r.euler_characteristic, 2);
}

TEST(Topology, BowtieOfTwoTetrahedraHasOneNonManifoldVertex) {
  // Two tetrahedra touching at the origin, which is vertex 0 of both.
  const SurfaceMesh a = tetrahedron({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  const SurfaceMesh b = tetrahedron({0, 0, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1});
  SurfaceMesh s = a;
  for (std::size_t v = 1; v < 4; ++v)
    s.points.push_back(b.points[v]);
  auto map = [](std::uint32_t v) { return v == 0 ? 0u : v + 3u; };
  for (const Triangle& t : b.triangles)
    s.triangles.push_back({map(t[0]), map(t[1]), map(t[2])});
  const TopologyReport r = check_topology(s);
  EXPECT_EQ(r.non_manifold_vertices, 1u) << r.summary();
  EXPECT_EQ(r.non_manifold_edges, 0u) << r.summary();
  EXPECT_EQ(r.boundary_edges, 0u);
  EXPECT_EQ(r.misoriented_edges, 0u);
  EXPECT_EQ(r.components, 1u);                         // connected through the shared vertex
  EXPECT_EQ(r.euler_characteristic, 3) << r.summary(); // 7 - 12 + 8
  EXPECT_FALSE(r.is_manifold());
}

TEST(Topology, TwoCubesSharingAnEdgeHaveOneNonManifoldEdge) {
  // Cubes [0,1]^3 and [1,2]x[1,2]x[0,1] share the edge x = y = 1; welding by position joins them.
  const SurfaceMesh joined = merged(box({0, 0, 0}, {1, 1, 1}), box({1, 1, 0}, {2, 2, 1}));
  std::vector<std::uint64_t> keys;
  for (const Point& p : joined.points)
    keys.push_back(static_cast<std::uint64_t>(std::lround(p[0]) * 9 + std::lround(p[1]) * 3 + std::lround(p[2])));
  const SurfaceMesh s = weld_by_key(joined.points, keys, joined.triangles);
  EXPECT_EQ(s.points.size(), 14u);
  const TopologyReport r = check_topology(s);
  EXPECT_EQ(r.non_manifold_edges, 1u) << r.summary();
  EXPECT_EQ(r.non_manifold_vertices, 2u) << r.summary(); // the ends of that edge
  EXPECT_EQ(r.boundary_edges, 0u);
  EXPECT_EQ(r.components, 1u);
  EXPECT_FALSE(r.is_manifold());
}

TEST(Topology, TwoTrianglesTouchingAtAVertexAreNonManifold) {
  SurfaceMesh s;
  s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  s.triangles = {{0, 1, 2}, {0, 3, 4}};
  const TopologyReport r = check_topology(s);
  EXPECT_EQ(r.non_manifold_vertices, 1u) << r.summary();
  EXPECT_EQ(r.boundary_edges, 6u);
  EXPECT_EQ(r.components, 1u);
}

TEST(Topology, DegenerateTrianglesAreCounted) {
  SurfaceMesh s = icosphere(1);
  const std::size_t clean = s.triangles.size();
  s.triangles.push_back({3, 3, 7}); // repeated index: ignored by the topology
  TopologyReport r = check_topology(s);
  EXPECT_EQ(r.degenerate_triangles, 1u) << r.summary();
  EXPECT_EQ(r.triangles, clean + 1);
  EXPECT_EQ(r.euler_characteristic, 2);
  EXPECT_EQ(r.boundary_edges, 0u);

  // Three distinct but collinear points, far from the origin: zero area up to rounding.
  SurfaceMesh line;
  line.points = {{5e5, 6e6, 1000}, {5e5 + 1, 6e6 + 2, 1003}, {5e5 + 2, 6e6 + 4, 1006}, {5e5, 6e6 + 1, 1000}};
  line.triangles = {{0, 1, 2}, {0, 1, 3}};
  r = check_topology(line);
  EXPECT_EQ(r.degenerate_triangles, 1u) << r.summary();
}

TEST(Topology, UnreferencedVerticesAndBadIndices) {
  SurfaceMesh s = icosphere(1);
  s.points.push_back({9, 9, 9});
  s.points.push_back({8, 8, 8});
  TopologyReport r = check_topology(s);
  EXPECT_EQ(r.unreferenced_vertices, 2u);
  EXPECT_EQ(r.vertices, s.points.size() - 2);
  EXPECT_EQ(r.euler_characteristic, 2);

  s.triangles.push_back({0, 1, static_cast<std::uint32_t>(s.points.size())});
  EXPECT_THROW(check_topology(s), InvalidArgument);
  EXPECT_THROW(split_components(s), InvalidArgument);
}

TEST(Topology, EmptySurface) {
  const TopologyReport r = check_topology(SurfaceMesh{});
  EXPECT_EQ(r.vertices, 0u);
  EXPECT_EQ(r.components, 0u);
  EXPECT_EQ(r.euler_characteristic, 0);
  EXPECT_TRUE(split_components(SurfaceMesh{}).empty());
}

TEST(Topology, ReportDoesNotDependOnNumbering) {
  // Permuting vertices and triangles (and rotating each triangle's corners) changes nothing.
  SurfaceMesh s = merged(torus(3.0, 1.0, 20, 10), icosphere(2, 1.0, {10, 0, 0}));
  std::swap(s.triangles[5][0], s.triangles[5][1]); // one defect to keep track of
  const TopologyReport before = check_topology(s);
  std::mt19937 rng(7);
  std::vector<std::uint32_t> perm(s.points.size());
  std::iota(perm.begin(), perm.end(), 0u);
  std::shuffle(perm.begin(), perm.end(), rng);
  SurfaceMesh p;
  p.points.resize(s.points.size());
  for (std::size_t v = 0; v < s.points.size(); ++v)
    p.points[perm[v]] = s.points[v];
  for (const Triangle& t : s.triangles) {
    const int rot = static_cast<int>(rng() % 3);
    p.triangles.push_back({perm[t[rot]], perm[t[(rot + 1) % 3]], perm[t[(rot + 2) % 3]]});
  }
  std::shuffle(p.triangles.begin(), p.triangles.end(), rng);
  const TopologyReport after = check_topology(p);
  EXPECT_EQ(before.summary(), after.summary());
  EXPECT_EQ(after.components, 2u);
  EXPECT_EQ(after.misoriented_edges, 3u);
  EXPECT_EQ(after.euler_characteristic, 2);
}

TEST(Components, TwoDisjointSpheresSplitInTwo) {
  const SurfaceMesh a = icosphere(2, 1.0, {0, 0, 0});
  const SurfaceMesh b = icosphere(3, 2.0, {5, 0, 0});
  SurfaceMesh s = merged(a, b);
  s.points.push_back({100, 100, 100}); // unreferenced: dropped
  EXPECT_EQ(check_topology(s).components, 2u);
  const std::vector<SurfaceMesh> parts = split_components(s);
  ASSERT_EQ(parts.size(), 2u);
  // Ordered by smallest vertex: a first. Same points and triangles, re-indexed.
  EXPECT_EQ(parts[0].points, a.points);
  EXPECT_EQ(parts[0].triangles, a.triangles);
  EXPECT_EQ(parts[1].points, b.points);
  EXPECT_EQ(parts[1].triangles, b.triangles);
  for (const SurfaceMesh& part : parts) {
    const TopologyReport r = check_topology(part);
    expect_clean_closed(r);
    EXPECT_EQ(r.euler_characteristic, 2);
  }
}

TEST(Components, InterleavedComponentsKeepTheirTriangles) {
  // Triangles of three bodies shuffled together: each part gets exactly its body's triangles.
  SurfaceMesh s = merged(merged(icosphere(1), torus(4, 1, 12, 6)), box({10, 10, 10}, {11, 12, 13}));
  std::mt19937 rng(3);
  std::shuffle(s.triangles.begin(), s.triangles.end(), rng);
  const std::vector<SurfaceMesh> parts = split_components(s);
  ASSERT_EQ(parts.size(), 3u);
  std::size_t triangles = 0;
  std::vector<long> euler;
  for (const SurfaceMesh& part : parts) {
    const TopologyReport r = check_topology(part);
    EXPECT_TRUE(r.is_closed_manifold()) << r.summary();
    EXPECT_EQ(r.components, 1u);
    triangles += part.triangles.size();
    euler.push_back(r.euler_characteristic);
  }
  EXPECT_EQ(triangles, s.triangles.size());
  EXPECT_EQ(euler, (std::vector<long>{2, 0, 2}));
  // Volumes of the parts add up to the whole.
  double sum = 0.0;
  for (const SurfaceMesh& part : parts)
    sum += enclosed_volume(part);
  EXPECT_NEAR(sum, enclosed_volume(s), 1e-9 * std::abs(sum));
}

TEST(Weld, MergesDuplicatedVertices) {
  const SurfaceMesh original = icosphere(2);
  const Unwelded u = unwelded(original);
  const TopologyReport loose = check_topology(u.surface);
  EXPECT_EQ(loose.boundary_edges, 3 * original.triangles.size());
  EXPECT_EQ(loose.components, original.triangles.size());

  const SurfaceMesh welded = weld_by_key(u.surface.points, u.keys, u.surface.triangles);
  EXPECT_EQ(welded.points.size(), original.points.size());
  const TopologyReport r = check_topology(welded);
  expect_clean_closed(r);
  EXPECT_EQ(r.euler_characteristic, 2);
  // Every welded triangle has the original's corners.
  ASSERT_EQ(welded.triangles.size(), original.triangles.size());
  for (std::size_t t = 0; t < original.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(welded.points[welded.triangles[t][c]], original.points[original.triangles[t][c]]);
  EXPECT_NEAR(enclosed_volume(welded), enclosed_volume(original), 1e-12);
}

TEST(Weld, DropsUnusedAndChecksInput) {
  const std::vector<Point> points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {7, 7, 7}, {1, 0, 0}};
  const std::vector<std::uint64_t> keys{10, 20, 30, 40, 20};
  const SurfaceMesh s = weld_by_key(points, keys, {{0, 4, 2}});
  ASSERT_EQ(s.points.size(), 3u); // the point of key 40 is unused, key 20 keeps its first point
  EXPECT_EQ(s.triangles, (std::vector<Triangle>{{0, 1, 2}}));
  EXPECT_EQ(s.points[1], points[1]);
  EXPECT_THROW(weld_by_key(points, {1, 2}, {{0, 1, 2}}), InvalidArgument);
  EXPECT_THROW(weld_by_key(points, keys, {{0, 1, 5}}), InvalidArgument);
}

} // namespace
} // namespace geotandem::mesh
