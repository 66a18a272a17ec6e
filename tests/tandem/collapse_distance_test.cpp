// White-box tests of the E0 guarantee's per-collapse bound (collapse_distance.hpp): on random
// patches around an edge ab (a ring of link vertices, bumpy heights), the bound d_c of a collapse
// to a random c is never below the two-sided Hausdorff distance between the patch before and after
// (measured independently by dense sampling), and it lets a flat patch slide for free.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "collapse_distance.hpp"
#include "geotandem/mesh/quality.hpp"
#include "geotandem/mesh/surface.hpp"
#include "triangle_insert.hpp"

namespace geotandem::tandem {
namespace {

using namespace detail;

// a at (-0.5, 0), b at (0.5, 0), `n` link vertices on an ellipse around them (counter-clockwise
// seen from +z), heights z = bump(x, y).
struct Patch {
  HalfedgeMesh mesh;
  VH a, b;
  std::vector<VH> ring;
  std::vector<VertexRecord> records;

  template <class Bump> Patch(int n, Bump bump, double phase) {
    const auto add = [&](double x, double y) { return mesh.add_vertex(HalfedgeMesh::Point(x, y, bump(x, y))); };
    a = add(-0.5, 0.0);
    b = add(0.5, 0.0);
    for (int k = 0; k < n; ++k) {
      const double t = phase + 2.0 * std::numbers::pi * k / n;
      ring.push_back(add(1.6 * std::cos(t), 1.1 * std::sin(t)));
    }
    const auto left = [&](VH v) { return mesh.point(v)[0] < 0.0; };
    const auto triangle = [&](VH p0, VH p1, VH p2) {
      EXPECT_TRUE(insert_triangle(mesh, p0, p1, p2).is_valid()) << "a triangle of the patch was refused";
    };
    for (int k = 0; k < n; ++k) {
      const VH p = ring[static_cast<std::size_t>(k)], q = ring[static_cast<std::size_t>((k + 1) % n)];
      if (left(p) && left(q)) {
        triangle(a, p, q);
      } else if (!left(p) && !left(q)) {
        triangle(b, p, q);
      } else if (!left(p) && left(q)) { // top: right to left
        triangle(b, p, q);
        triangle(a, b, q);
      } else { // bottom: left to right
        triangle(a, p, q);
        triangle(b, a, q);
      }
    }
    records.resize(mesh.n_vertices());
  }

  HH ab() const { return find_halfedge(mesh, a, b); }

  // The patch as plain triangles, with a and b moved to c (collapsed) or not.
  mesh::SurfaceMesh surface(const Vec3* c) const {
    mesh::SurfaceMesh s;
    for (std::size_t i = 0; i < mesh.n_vertices(); ++i) {
      const auto& p = mesh.point(VH(static_cast<int>(i)));
      s.points.push_back({p[0], p[1], p[2]});
    }
    if (c) s.points.push_back(*c);
    const auto index = [&](VH v) {
      if (c && (v == a || v == b)) return static_cast<std::uint32_t>(s.points.size() - 1);
      return static_cast<std::uint32_t>(v.idx());
    };
    for (std::size_t f = 0; f < mesh.n_faces(); ++f) {
      const HH h = mesh.halfedge_handle(FH(static_cast<int>(f)));
      const std::array<std::uint32_t, 3> t{index(mesh.from_vertex_handle(h)), index(mesh.to_vertex_handle(h)),
                                           index(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)))};
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue; // abx, aby vanish
      s.triangles.push_back(t);
    }
    return s;
  }
};

TEST(CollapseDistance, BoundsTheDistanceBetweenThePatchesBeforeAndAfter) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int projected_wins = 0;
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const double amp = 0.4 * std::abs(unit(rng)), fx = 1.0 + unit(rng), fy = 1.5 + unit(rng), tilt = unit(rng);
    const auto bump = [&](double x, double y) { return tilt * x + amp * std::sin(fx * x + 0.3) * std::cos(fy * y); };
    const Patch patch(8 + trial % 7, bump, 0.2 + 0.1 * unit(rng));
    const HH h = patch.ab();
    ASSERT_TRUE(h.is_valid());
    const Vec3 c{0.6 * unit(rng), 0.3 * unit(rng), bump(0.0, 0.0) + 0.3 * unit(rng)};
    CollapseDistance distance;
    const double bound = distance.tolerance(patch.mesh, h, c, patch.mesh.points(), patch.records.data());
    const double simplicial =
        CollapseDistance::simplicial(to_vec(patch.mesh.point(patch.a)), 0.0, to_vec(patch.mesh.point(patch.b)), 0.0, c);
    EXPECT_LE(bound, simplicial * (1.0 + 1e-9) + 1e-12);
    if (bound < 0.9 * simplicial) ++projected_wins;
    const mesh::SurfaceMesh before = patch.surface(nullptr), after = patch.surface(&c);
    const double measured = mesh::hausdorff_distance(before, after, 60).max;
    EXPECT_LE(measured, bound + 1e-9) << "bound " << bound << ", simplicial " << simplicial;
  }
  EXPECT_GT(projected_wins, 100) << "the projection map should usually beat the simplicial one";
}

TEST(CollapseDistance, AFlatPatchSlidesForFree) {
  const Patch patch(
      10, [](double, double) { return 0.0; }, 0.25);
  CollapseDistance distance;
  const double bound =
      distance.tolerance(patch.mesh, patch.ab(), Vec3{0.2, 0.1, 0.0}, patch.mesh.points(), patch.records.data());
  EXPECT_LT(bound, 1e-9);
  // Lifting c off the plane costs at least the lift.
  const double lifted =
      distance.tolerance(patch.mesh, patch.ab(), Vec3{0.2, 0.1, 0.3}, patch.mesh.points(), patch.records.data());
  EXPECT_GE(lifted, 0.3);
  EXPECT_LT(lifted, 0.3 + 1e-6);
}

TEST(CollapseDistance, EarlierBoundsAddUp) {
  Patch patch(
      10, [](double, double) { return 0.0; }, 0.25);
  for (auto& r : patch.records)
    r.tolerance = 0.1;
  CollapseDistance distance;
  // Everything at 0.1 and nothing moves off the plane: c needs 0.1 to cover the old tolerance.
  const double flat =
      distance.tolerance(patch.mesh, patch.ab(), Vec3{0.0, 0.0, 0.0}, patch.mesh.points(), patch.records.data());
  EXPECT_NEAR(flat, 0.1, 1e-6);
  const double lifted =
      distance.tolerance(patch.mesh, patch.ab(), Vec3{0.0, 0.0, 0.2}, patch.mesh.points(), patch.records.data());
  EXPECT_GE(lifted, 0.3 - 1e-9);
}

} // namespace
} // namespace geotandem::tandem
