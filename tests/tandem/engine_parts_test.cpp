// The engine's parts on their own, on closed meshes built here. EdgeCost (edge_cost.hpp): the
// volume plane it derives from the running per-vertex sums against the enclosed volume of the
// collapsed triangles computed from scratch, and the sums against a recomputation.
// ComponentReader (component_reader.hpp): a component read out of a mesh holding several is that
// component, whole, closed and oriented as it was.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "component_reader.hpp"
#include "edge_cost.hpp"
#include "triangle_insert.hpp"

namespace geotandem::tandem {
namespace {

using detail::FH;
using detail::HH;
using detail::Vec3;
using detail::VH;
using detail::operator+;
using detail::operator-;
using detail::operator*;
using Triangle = std::array<int, 3>;

// An octahedron subdivided twice (66 vertices, 128 triangles, outward and counter-clockwise),
// radius 5 around (20, 30, 40), each vertex moved by up to 0.4 on each axis.
struct ClosedSurface {
  std::vector<Vec3> points;
  std::vector<Triangle> triangles;
};

ClosedSurface jittered_octahedron(unsigned seed) {
  ClosedSurface s;
  s.points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  s.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int level = 0; level < 2; ++level) {
    std::map<std::pair<int, int>, int> middle;
    const auto mid = [&](int i, int j) {
      const auto key = std::minmax(i, j);
      const auto found = middle.find(key);
      if (found != middle.end()) return found->second;
      Vec3 m = s.points[static_cast<std::size_t>(i)] + s.points[static_cast<std::size_t>(j)];
      m = (1.0 / detail::norm(m)) * m;
      s.points.push_back(m);
      const int k = static_cast<int>(s.points.size() - 1);
      middle.emplace(key, k);
      return k;
    };
    std::vector<Triangle> finer;
    for (const Triangle& t : s.triangles) {
      const int a = mid(t[0], t[1]), b = mid(t[1], t[2]), c = mid(t[2], t[0]);
      finer.insert(finer.end(), {{t[0], a, c}, {a, t[1], b}, {c, b, t[2]}, {a, b, c}});
    }
    s.triangles = std::move(finer);
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.4, 0.4);
  for (Vec3& p : s.points)
    p = Vec3{20.0 + 5.0 * p[0] + jitter(rng), 30.0 + 5.0 * p[1] + jitter(rng), 40.0 + 5.0 * p[2] + jitter(rng)};
  return s;
}

// Six times the enclosed volume, from scratch.
double six_volume(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles) {
  double sum = 0.0;
  for (const Triangle& t : triangles) {
    const Vec3 &p = points[static_cast<std::size_t>(t[0])], &q = points[static_cast<std::size_t>(t[1])],
               &r = points[static_cast<std::size_t>(t[2])];
    sum += detail::dot(p, detail::cross(q, r));
  }
  return sum;
}

struct Built {
  detail::HalfedgeMesh mesh;
  std::vector<FH> faces;
};

void build(const ClosedSurface& s, Built& out) {
  for (const Vec3& p : s.points)
    out.mesh.add_vertex(detail::HalfedgeMesh::Point(p[0], p[1], p[2]));
  for (const Triangle& t : s.triangles) {
    const FH f = detail::insert_triangle(out.mesh, VH(t[0]), VH(t[1]), VH(t[2]));
    ASSERT_TRUE(f.is_valid());
    out.faces.push_back(f);
  }
}

// Every face's terms into its corners' sums, relative to `origin`: what an engine holds after
// appending the faces.
void add_all_faces(detail::EdgeCost& cost, Built& b, const Vec3& origin) {
  cost.set_origin(origin);
  for (FH f : b.faces)
    cost.add_face_terms(f);
}

SimplifyOptions volume_options() {
  SimplifyOptions options;
  options.max_error = 0.5;
  options.preserve_volume = true;
  return options;
}

// A jittered octahedron in a working mesh and its EdgeCost (cube faces at 0 and `cube_hi`), with
// every face's terms in.
struct Costed {
  ClosedSurface s;
  Built b;
  std::optional<detail::EdgeCost> cost;
};

void make_costed(unsigned seed, double cube_hi, const Vec3& origin, Costed& out) {
  out.s = jittered_octahedron(seed);
  build(out.s, out.b);
  out.cost.emplace(out.b.mesh, volume_options(), std::array<double, 3>{cube_hi, cube_hi, cube_hi});
  add_all_faces(*out.cost, out.b, origin);
}

TEST(EdgeCost, VolumePlaneIsWhereTheCollapseKeepsTheEnclosedVolume) {
  for (unsigned seed : {1u, 2u, 3u}) {
    Costed costed;
    make_costed(seed, 511.0, {16.0, 24.0, 32.0}, costed); // a block's corner: sums are relative to it
    const ClosedSurface& s = costed.s;
    Built& b = costed.b;
    detail::EdgeCost& cost = *costed.cost;
    const double before = six_volume(s.points, s.triangles);

    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (std::size_t e = 0; e < b.mesh.n_edges(); ++e) {
      const HH h = detail::HalfedgeMesh::halfedge_handle(detail::EH(static_cast<int>(e)), 0);
      const int ia = b.mesh.from_vertex_handle(h).idx(), ib = b.mesh.to_vertex_handle(h).idx();
      detail::CostInputs in;
      ASSERT_TRUE(cost.inputs(h, in));
      ASSERT_TRUE(in.preserve_volume);
      EXPECT_EQ(in.fixed_axes, 0u);
      const Vec3 mid = 0.5 * (in.a + in.b);
      // Any c: six times the change of volume is N.(c - mid) - K (docs/algorithm.md, the volume
      // plane), so K = 0 on the plane. c on the plane, then off it.
      const Vec3 n = in.volume_normal;
      ASSERT_GT(detail::norm(n), 0.0);
      Vec3 along{u(rng), u(rng), u(rng)};
      along = along - (detail::dot(along, n) / detail::dot(n, n)) * n;
      const Vec3 on_plane = mid + (in.volume_offset / detail::dot(n, n)) * n + along;
      for (const Vec3& c : {on_plane, Vec3(on_plane + (u(rng) / detail::norm(n)) * n)}) {
        std::vector<Vec3> points = s.points;
        points[static_cast<std::size_t>(ia)] = c;
        points[static_cast<std::size_t>(ib)] = c;
        std::vector<Triangle> kept;
        for (Triangle t : s.triangles) {
          const bool has_a = t[0] == ia || t[1] == ia || t[2] == ia, has_b = t[0] == ib || t[1] == ib || t[2] == ib;
          if (!(has_a && has_b)) kept.push_back(t); // the two triangles of ab vanish
        }
        const double change = six_volume(points, kept) - before;
        const double predicted = detail::dot(n, c - mid) - in.volume_offset;
        EXPECT_NEAR(change, predicted, 1e-9 * std::abs(before)) << "seed " << seed << ", edge " << e;
      }
    }
  }
}

TEST(EdgeCost, RunningSumsMatchARecomputationAfterFacesLeaveAndReturn) {
  Costed costed;
  make_costed(7, 511.0, {16.0, 24.0, 32.0}, costed);
  const ClosedSurface& s = costed.s;
  Built& b = costed.b;
  detail::EdgeCost& cost = *costed.cost;
  // Every other face leaves its corners' sums (but those of vertices 0 and 1) and comes back, as
  // the faces around a collapse do.
  for (std::size_t k = 0; k < b.faces.size(); k += 2)
    cost.remove_face_terms(b.faces[k], VH(0), VH(1));
  for (std::size_t k = 0; k < b.faces.size(); k += 2)
    cost.add_face_terms(b.faces[k]);
  const std::vector<detail::VertexRecord> running(b.mesh.vertex_records(),
                                                  b.mesh.vertex_records() + b.mesh.n_vertices());
  cost.recompute_face_terms();
  const detail::VertexRecord* fresh = b.mesh.vertex_records();
  for (std::size_t v = 2; v < running.size(); ++v) {
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_NEAR(running[v].cross_sum[i], fresh[v].cross_sum[i], 1e-9 * (1.0 + std::abs(fresh[v].cross_sum[i])));
      EXPECT_NEAR(running[v].link_sum[i], fresh[v].link_sum[i], 1e-9 * (1.0 + std::abs(fresh[v].link_sum[i])));
    }
    EXPECT_NEAR(running[v].isotropy.area, fresh[v].isotropy.area, 1e-9 * fresh[v].isotropy.area);
  }
  // Vertices 0 and 1 kept the terms of the faces that left: theirs are counted twice.
  for (int v = 0; v < 2; ++v) {
    double twice = 0.0;
    for (std::size_t k = 0; k < s.triangles.size(); k += 2) {
      const Triangle& t = s.triangles[k];
      if (t[0] != v && t[1] != v && t[2] != v) continue;
      const Vec3 &p = s.points[static_cast<std::size_t>(t[0])], &q = s.points[static_cast<std::size_t>(t[1])],
                 &r = s.points[static_cast<std::size_t>(t[2])];
      twice += 0.5 * detail::norm(detail::cross(q - p, r - p));
    }
    EXPECT_GT(twice, 0.0);
    const auto i = static_cast<std::size_t>(v);
    EXPECT_NEAR(running[i].isotropy.area - fresh[i].isotropy.area, twice, 1e-9 * fresh[i].isotropy.area);
  }
}

TEST(EdgeCost, CubeFacesFixTheCoordinateOrForbidTheCollapse) {
  Costed costed;
  make_costed(3, 63.0, {0.0, 0.0, 0.0}, costed);
  Built& b = costed.b;
  detail::EdgeCost& cost = *costed.cost;
  const HH h = b.mesh.halfedge_handle(VH(0));
  const int ia = b.mesh.from_vertex_handle(h).idx(), ib = b.mesh.to_vertex_handle(h).idx();
  detail::VertexRecord* r = b.mesh.vertex_records();
  // a on the far z face: c keeps z = 63 (the cube's last index).
  r[ia].border = 2u << 4;
  detail::CostInputs in;
  ASSERT_TRUE(cost.inputs(h, in));
  EXPECT_EQ(in.fixed_axes, 4u);
  EXPECT_EQ(in.fixed_value[2], 63.0);
  // b on the near z face as well: both sides of one axis, never collapsed (counted as such).
  r[ib].border = 1u << 4;
  EXPECT_FALSE(cost.inputs(h, in));
  SimplifyCounters counters;
  detail::Candidate candidate;
  EXPECT_FALSE(cost.evaluate(h, candidate, counters));
  EXPECT_EQ(counters.rejected_border, 1u);
  EXPECT_EQ(counters.evaluations, 0u);
}

TEST(ComponentReader, ReadsOneComponentWholeClosedAndOrientedAsItWas) {
  // Three jittered octahedra side by side in one mesh, their vertices interleaved so that a
  // component's vertices are not a range of numbers.
  std::vector<ClosedSurface> bodies;
  for (unsigned seed : {4u, 5u, 6u})
    bodies.push_back(jittered_octahedron(seed));
  const std::size_t n = bodies[0].points.size();
  detail::HalfedgeMesh mesh;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const Vec3& p = bodies[b].points[i];
      mesh.add_vertex(detail::HalfedgeMesh::Point(p[0] + 20.0 * static_cast<double>(b), p[1], p[2]));
    }
  const auto vertex = [&](std::size_t b, int i) { return VH(static_cast<int>(static_cast<std::size_t>(i) * 3 + b)); };
  for (std::size_t b = 0; b < bodies.size(); ++b)
    for (const Triangle& t : bodies[b].triangles)
      ASSERT_TRUE(detail::insert_triangle(mesh, vertex(b, t[0]), vertex(b, t[1]), vertex(b, t[2])).is_valid());

  detail::ComponentReader reader;
  detail::VertexMarks marks;
  marks.ensure(mesh.n_vertices());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    std::vector<VH> vertices;
    std::vector<FH> faces;
    const mesh::SurfaceMesh surface = reader.read(mesh, mesh.points(), vertex(b, 17), marks, vertices, faces);
    ASSERT_EQ(surface.points.size(), n);
    ASSERT_EQ(surface.triangles.size(), bodies[b].triangles.size());
    ASSERT_EQ(vertices.size(), n);
    ASSERT_EQ(faces.size(), bodies[b].triangles.size());
    EXPECT_EQ(vertices.front(), vertex(b, 17));
    std::set<int> seen;
    for (std::size_t k = 0; k < vertices.size(); ++k) {
      EXPECT_EQ(static_cast<std::size_t>(vertices[k].idx()) % 3, b); // only this body's vertices
      EXPECT_TRUE(seen.insert(vertices[k].idx()).second);            // each once
      const Vec3 p = detail::to_vec(mesh.points()[vertices[k].idx()]);
      EXPECT_EQ(surface.points[k], p); // numbered in the order visited
    }
    // Closed and consistently oriented: every directed edge once, and its opposite once.
    std::set<std::pair<std::uint32_t, std::uint32_t>> directed;
    for (const auto& t : surface.triangles)
      for (int k = 0; k < 3; ++k)
        EXPECT_TRUE(directed.insert({t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]}).second);
    for (const auto& [u, v] : directed)
      EXPECT_TRUE(directed.count({v, u})) << u << " " << v;
    // The same enclosed volume as the body it was built from (so the orientation was kept).
    std::vector<Vec3> shifted = bodies[b].points;
    for (Vec3& p : shifted)
      p[0] += 20.0 * static_cast<double>(b);
    std::vector<Triangle> triangles;
    for (const auto& t : surface.triangles)
      triangles.push_back({static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
    EXPECT_NEAR(six_volume(surface.points, triangles), six_volume(shifted, bodies[b].triangles),
                1e-9 * six_volume(shifted, bodies[b].triangles));
    EXPECT_GT(six_volume(surface.points, triangles), 0.0);
  }
}

} // namespace
} // namespace geotandem::tandem
