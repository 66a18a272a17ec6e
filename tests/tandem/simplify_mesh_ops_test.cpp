// White-box tests of the connectivity operations written against HalfedgeMesh: triangle insertion in
// any order, the link condition and the collapse. Checked against the halfedge invariants and the
// Euler characteristic, on closed surfaces from marching cubes.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include "collapse_ops.hpp"
#include "geotandem/mesh/topology.hpp"
#include "simplify_fixtures.hpp"
#include "triangle_insert.hpp"

namespace geotandem::tandem {
namespace {

using namespace detail;

mesh::SurfaceMesh torus_surface() {
  const fixtures::Input input(fixtures::torus({12.3, 11.8, 7.6}, 7.0, 3.2), {25, 24, 16});
  return input.full(input.cells(), 0);
}

// The mesh of `s`, its triangles inserted in order.
void build(HalfedgeMesh& m, const mesh::SurfaceMesh& s) {
  for (const auto& p : s.points)
    m.add_vertex(HalfedgeMesh::Point(p[0], p[1], p[2]));
  for (const auto& t : s.triangles)
    ASSERT_TRUE(insert_triangle(m, VH(static_cast<int>(t[0])), VH(static_cast<int>(t[1])), VH(static_cast<int>(t[2])))
                    .is_valid());
}

// Halfedge invariants of the live part of the mesh; returns V - E + F over live elements.
long check_connectivity(const HalfedgeMesh& m) {
  long v = 0, e = 0, f = 0;
  for (std::size_t i = 0; i < m.n_edges(); ++i) {
    const EH eh(static_cast<int>(i));
    if (m.deleted(eh)) continue;
    ++e;
    for (int side = 0; side < 2; ++side) {
      const HH h = m.halfedge_handle(eh, static_cast<unsigned>(side));
      EXPECT_EQ(m.prev_halfedge_handle(m.next_halfedge_handle(h)), h);
      EXPECT_EQ(m.from_vertex_handle(m.next_halfedge_handle(h)), m.to_vertex_handle(h));
      EXPECT_EQ(m.face_handle(m.next_halfedge_handle(h)), m.face_handle(h));
      EXPECT_FALSE(m.deleted(m.to_vertex_handle(h)));
      if (m.face_handle(h).is_valid()) {
        EXPECT_FALSE(m.deleted(m.face_handle(h)));
        EXPECT_EQ(m.next_halfedge_handle(m.next_halfedge_handle(m.next_halfedge_handle(h))), h) << "not a triangle";
      }
    }
  }
  for (std::size_t i = 0; i < m.n_faces(); ++i)
    if (!m.deleted(FH(static_cast<int>(i)))) ++f;
  for (std::size_t i = 0; i < m.n_vertices(); ++i) {
    const VH vh(static_cast<int>(i));
    if (m.deleted(vh)) continue;
    const HH start = m.halfedge_handle(vh);
    if (!start.is_valid()) continue; // no triangle yet
    ++v;
    EXPECT_EQ(m.from_vertex_handle(start), vh);
    // The rotation visits each neighbour once and comes back.
    std::set<int> seen;
    HH g = start;
    int steps = 0;
    bool any_boundary = false;
    do {
      EXPECT_TRUE(seen.insert(m.to_vertex_handle(g).idx()).second) << "neighbour twice around vertex " << i;
      any_boundary = any_boundary || !m.face_handle(g).is_valid();
      g = next_outgoing(m, g);
    } while (g != start && ++steps < 1000);
    EXPECT_LT(steps, 1000);
    // A boundary vertex points to a boundary halfedge.
    if (any_boundary) {
      EXPECT_FALSE(m.face_handle(start).is_valid());
    }
  }
  return v - e + f;
}

// A random live halfedge whose collapse passes the link condition, or an invalid handle.
HH random_collapsible(const HalfedgeMesh& m, VertexMarks& marks, std::mt19937& rng) {
  const EH e(static_cast<int>(rng() % m.n_edges()));
  if (m.deleted(e)) return HH();
  const HH h = m.halfedge_handle(e, rng() % 2);
  return link_condition_ok(m, h, marks) ? h : HH();
}

// The live triangles as corner positions, starting from the smallest corner.
std::set<std::array<std::array<double, 3>, 3>> live_triangles(const HalfedgeMesh& m) {
  std::set<std::array<std::array<double, 3>, 3>> out;
  for (std::size_t i = 0; i < m.n_faces(); ++i) {
    const FH f(static_cast<int>(i));
    if (m.deleted(f)) continue;
    const HH h = m.halfedge_handle(f);
    std::array<std::array<double, 3>, 3> t;
    const VH corners[3] = {m.from_vertex_handle(h), m.to_vertex_handle(h),
                           m.to_vertex_handle(m.next_halfedge_handle(h))};
    for (int k = 0; k < 3; ++k) {
      const auto& p = m.point(corners[k]);
      t[static_cast<std::size_t>(k)] = {p[0], p[1], p[2]};
    }
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.insert(t);
  }
  return out;
}

// Random legal collapses, then compaction: the same live surface, nothing dead; no spare room when
// it gives back, all the room it had when it keeps it (for the layers still to come).
void collapse_then_compact(HalfedgeMesh& m, long euler, unsigned seed, bool give_back) {
  VertexMarks marks;
  marks.ensure(m.n_vertices());
  std::mt19937 rng(seed);
  std::size_t collapses = 0;
  for (int attempt = 0; attempt < 4000 && collapses < m.n_vertices() / 2; ++attempt) {
    const HH h = random_collapsible(m, marks, rng);
    if (!h.is_valid()) continue;
    collapse_halfedge(m, h);
    ++collapses;
  }
  ASSERT_GT(collapses, m.n_vertices() / 4);
  const auto before = live_triangles(m);
  std::vector<HalfedgeMesh::Point> points(m.points(), m.points() + m.n_vertices());
  std::vector<bool> alive;
  for (std::size_t i = 0; i < m.n_vertices(); ++i)
    alive.push_back(!m.deleted(VH(static_cast<int>(i))));
  const std::size_t live_vertices = static_cast<std::size_t>(std::count(alive.begin(), alive.end(), true));

  const std::size_t rooms[3] = {m.vertex_capacity(), m.edge_capacity(), m.face_capacity()};
  const std::vector<std::int32_t> moved = m.compact(give_back);
  ASSERT_EQ(moved.size(), alive.size());
  EXPECT_EQ(m.n_vertices(), live_vertices);
  EXPECT_EQ(m.n_faces(), before.size());
  EXPECT_LT(m.n_vertices(), rooms[0]);
  if (give_back) {
    EXPECT_EQ(m.vertex_capacity(), m.n_vertices());
    EXPECT_EQ(m.edge_capacity(), m.n_edges());
    EXPECT_EQ(m.face_capacity(), m.n_faces());
  } else {
    EXPECT_EQ(m.vertex_capacity(), rooms[0]);
    EXPECT_EQ(m.edge_capacity(), rooms[1]);
    EXPECT_EQ(m.face_capacity(), rooms[2]);
  }
  for (std::size_t i = 0; i < m.n_edges(); ++i)
    EXPECT_FALSE(m.deleted(EH(static_cast<int>(i))));
  std::int32_t next = 0;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    if (!alive[i]) {
      EXPECT_EQ(moved[i], -1);
      continue;
    }
    ASSERT_EQ(moved[i], next++) << "live vertices keep their order";
    EXPECT_EQ(m.point(VH(moved[i])), points[i]);
  }
  EXPECT_EQ(check_connectivity(m), euler);
  EXPECT_EQ(live_triangles(m), before);
}

TEST(TriangleInsert, AnyOrderOfAClosedSurfaceGoesIn) {
  const mesh::SurfaceMesh s = torus_surface();
  ASSERT_GT(s.triangle_count(), 500u);
  for (unsigned seed : {1u, 2u, 3u}) {
    std::vector<std::size_t> order(s.triangle_count());
    for (std::size_t i = 0; i < order.size(); ++i)
      order[i] = i;
    std::shuffle(order.begin(), order.end(), std::mt19937(seed));
    HalfedgeMesh m;
    for (const auto& p : s.points)
      m.add_vertex(HalfedgeMesh::Point(p[0], p[1], p[2]));
    std::size_t step = 0;
    for (std::size_t t : order) {
      const auto& tri = s.triangles[t];
      const FH f =
          insert_triangle(m, VH(static_cast<int>(tri[0])), VH(static_cast<int>(tri[1])), VH(static_cast<int>(tri[2])));
      ASSERT_TRUE(f.is_valid()) << "triangle " << t << " refused at step " << step << ", seed " << seed;
      ++step;
      if (step == order.size() / 2) check_connectivity(m); // half-built: many fans per vertex
    }
    EXPECT_EQ(check_connectivity(m), 0); // a torus
    for (std::size_t i = 0; i < m.n_halfedges(); ++i)
      EXPECT_TRUE(m.face_handle(HH(static_cast<int>(i))).is_valid()) << "closed surface";
    // The triangles come out as they went in.
    std::set<std::array<int, 3>> in, out;
    auto canonical = [](std::array<int, 3> t) {
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      return t;
    };
    for (const auto& t : s.triangles)
      in.insert(canonical({static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])}));
    for (std::size_t i = 0; i < m.n_faces(); ++i) {
      const HH h = m.halfedge_handle(FH(static_cast<int>(i)));
      out.insert(canonical({m.from_vertex_handle(h).idx(), m.to_vertex_handle(h).idx(),
                            m.to_vertex_handle(m.next_halfedge_handle(h)).idx()}));
    }
    EXPECT_EQ(in, out);
  }
}

TEST(TriangleInsert, RefusesNonManifoldAndMisorientedTriangles) {
  HalfedgeMesh m;
  VH v[6];
  for (int i = 0; i < 6; ++i)
    v[i] = m.add_vertex(HalfedgeMesh::Point(i, i * i, 0));
  ASSERT_TRUE(insert_triangle(m, v[0], v[1], v[2]).is_valid());
  ASSERT_TRUE(insert_triangle(m, v[0], v[2], v[3]).is_valid());
  // The edge 0 -> 1 is used in this direction already.
  EXPECT_FALSE(insert_triangle(m, v[0], v[1], v[4]).is_valid());
  // Close the fan around 0 with 0-3-4 and 0-4-1, then 0 is interior: nothing more can touch it.
  ASSERT_TRUE(insert_triangle(m, v[0], v[3], v[4]).is_valid());
  ASSERT_TRUE(insert_triangle(m, v[0], v[4], v[1]).is_valid());
  EXPECT_FALSE(insert_triangle(m, v[0], v[5], v[2]).is_valid());
  check_connectivity(m);
}

TEST(CollapseOps, RandomLegalCollapsesKeepTheTopology) {
  const mesh::SurfaceMesh s = torus_surface();
  HalfedgeMesh m;
  ASSERT_NO_FATAL_FAILURE(build(m, s));
  VertexMarks marks;
  marks.ensure(m.n_vertices());
  std::mt19937 rng(11);
  std::size_t collapses = 0, refused = 0;
  for (int attempt = 0; attempt < 20000 && collapses < s.points.size() - 40; ++attempt) {
    const EH e(static_cast<int>(rng() % m.n_edges()));
    if (m.deleted(e)) continue;
    const HH h = m.halfedge_handle(e, rng() % 2);
    if (!link_condition_ok(m, h, marks)) {
      ++refused;
      continue;
    }
    const CollapseResult r = collapse_halfedge(m, h);
    EXPECT_EQ(r.removed_edge_count, 3);
    EXPECT_EQ(r.removed_face_count, 2);
    ++collapses;
    if (collapses % 200 == 0) {
      ASSERT_EQ(check_connectivity(m), 0);
    }
  }
  EXPECT_EQ(check_connectivity(m), 0);
  EXPECT_GT(collapses, s.points.size() / 2);
  EXPECT_GT(refused, 0u) << "near the end, most collapses would change the topology";
}

TEST(CollapseOps, BoundaryCollapsesKeepADisc) {
  // A flat disc: collapses along and across its boundary keep one disc (Euler characteristic 1).
  HalfedgeMesh m;
  const int n = 9;
  std::vector<VH> grid;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      grid.push_back(m.add_vertex(HalfedgeMesh::Point(i, j, 0)));
  auto at = [&](int i, int j) { return grid[static_cast<std::size_t>(i * n + j)]; };
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      ASSERT_TRUE(insert_triangle(m, at(i, j), at(i + 1, j), at(i + 1, j + 1)).is_valid());
      ASSERT_TRUE(insert_triangle(m, at(i, j), at(i + 1, j + 1), at(i, j + 1)).is_valid());
    }
  ASSERT_EQ(check_connectivity(m), 1);
  VertexMarks marks;
  marks.ensure(m.n_vertices());
  std::mt19937 rng(5);
  std::size_t collapses = 0;
  for (int attempt = 0; attempt < 5000; ++attempt) {
    const HH h = random_collapsible(m, marks, rng);
    if (!h.is_valid()) continue;
    collapse_halfedge(m, h);
    ++collapses;
    ASSERT_EQ(check_connectivity(m), 1) << "after " << collapses << " collapses";
  }
  EXPECT_GT(collapses, 50u);
}

TEST(HalfedgeMesh, CompactionInPlaceKeepsTheLiveSurfaceOfATorus) {
  const mesh::SurfaceMesh s = torus_surface();
  for (const bool give_back : {true, false}) {
    HalfedgeMesh m;
    ASSERT_NO_FATAL_FAILURE(build(m, s));
    collapse_then_compact(m, 0, 3, give_back);
  }
}

TEST(HalfedgeMesh, CompactionInPlaceKeepsTheBoundaryOfADisc) {
  for (const bool give_back : {true, false}) {
    HalfedgeMesh m;
    const int n = 12;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        m.add_vertex(HalfedgeMesh::Point(i, j, 0.1 * ((i * j) % 3)));
    const auto at = [&](int i, int j) { return VH(i * n + j); };
    for (int i = 0; i + 1 < n; ++i)
      for (int j = 0; j + 1 < n; ++j) {
        ASSERT_TRUE(insert_triangle(m, at(i, j), at(i + 1, j), at(i + 1, j + 1)).is_valid());
        ASSERT_TRUE(insert_triangle(m, at(i, j), at(i + 1, j + 1), at(i, j + 1)).is_valid());
      }
    collapse_then_compact(m, 1, 8, give_back);
  }
}

} // namespace
} // namespace geotandem::tandem
