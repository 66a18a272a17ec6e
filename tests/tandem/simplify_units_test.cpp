// Unit tests of the simplifier's pieces: the Attali cost, the id map, the component table (the
// edges' queues: edge_queues_test.cpp; regions and open faces: region_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "attali_cost.hpp"
#include "component_table.hpp"
#include "id_map.hpp"

namespace geotandem::tandem {
namespace {

using detail::Vec3;
using detail::operator+;
using detail::operator-;
using detail::operator*;

// ------------------------------------------------------------------------------------- cost

// A flat square patch z = 2 of two triangles around the edge a = (0,0,2), b = (1,0,2).
detail::CostInputs flat_patch(Vec3 a, Vec3 b) {
  detail::CostInputs in;
  in.a = a;
  in.b = b;
  const Vec3 corners[4] = {{-1, -1, 2}, {2, -1, 2}, {2, 1, 2}, {-1, 1, 2}};
  for (int t = 0; t < 2; ++t) {
    const Vec3 p0 = corners[0], p1 = corners[t + 1], p2 = corners[t + 2];
    const double area = 0.5 * detail::norm(detail::cross(detail::operator-(p1, p0), detail::operator-(p2, p0)));
    in.shape.add_plane({0, 0, 1}, -2.0, area);
    in.weight += area;
    in.isotropy += detail::Isotropy::of_triangle(p0, p1, p2);
  }
  return in;
}

TEST(AttaliCost, FlatPatchCostsNothingOnItsPlaneForEveryAlpha) {
  for (double alpha : {0.0, 0.4, 1.0}) {
    const detail::AttaliCost cost(0.5, alpha);
    const detail::CostInputs in = flat_patch({0, 0, 2}, {1, 0, 2});
    const auto prepared = cost.prepare(in);
    const detail::Candidate c = cost.best(prepared);
    EXPECT_NEAR(c.position[2], 2.0, 1e-9) << "alpha " << alpha;
    EXPECT_NEAR(c.shape_error, 0.0, 1e-6) << "alpha " << alpha;
    // With alpha = 0 the plane is a whole valley of minimisers: the pseudo-inverse keeps c at
    // the midpoint; with alpha > 0 the isotropy term pulls c to the patch's barycentre.
    if (alpha == 0.0) {
      EXPECT_NEAR(c.position[0], 0.5, 1e-9);
      EXPECT_NEAR(c.position[1], 0.0, 1e-9);
    }
    if (alpha == 1.0) {
      EXPECT_NEAR(c.position[0], 0.5, 1e-9);
      EXPECT_NEAR(c.position[1], 0.0, 1e-9);
    }
    // Off the plane the shape error is the distance.
    const detail::Candidate off = cost.at(prepared, {0.5, 0.0, 2.3});
    EXPECT_NEAR(off.shape_error, 0.3, 1e-9);
    EXPECT_GE(off.cost, c.cost);
  }
}

TEST(AttaliCost, CornerOfTwoPlanesIsFoundAndBounded) {
  // Planes x = 0 and y = 0 with equal weight: the minimiser of the shape term lies on the line
  // x = y = 0; alpha = 0 picks the point of that line nearest the midpoint.
  detail::CostInputs in;
  in.a = {0.2, 0.1, 3.0};
  in.b = {0.1, 0.3, 5.0};
  in.shape.add_plane({1, 0, 0}, 0.0, 1.0);
  in.shape.add_plane({0, 1, 0}, 0.0, 1.0);
  in.weight = 2.0;
  in.isotropy = detail::Isotropy::of_triangle({0, 0, 3}, {0, 1, 4}, {1, 0, 5});
  const detail::AttaliCost cost(0.5, 0.0);
  const auto p = cost.prepare(in);
  const detail::Candidate c = cost.best(p);
  EXPECT_NEAR(c.position[0], 0.0, 1e-9);
  EXPECT_NEAR(c.position[1], 0.0, 1e-9);
  EXPECT_NEAR(c.position[2], 4.0, 1e-9);
  EXPECT_NEAR(c.shape_error, 0.0, 1e-9);
  // The best of the endpoints is never better than the optimum.
  EXPECT_GE(cost.best_fallback(p).cost, c.cost - 1e-12);
}

TEST(AttaliCost, FixedAxesKeepTheCandidateOnTheCubeFace) {
  detail::CostInputs in = flat_patch({0, 0, 2}, {1, 0, 2});
  in.fixed_axes = 1u; // x = 0
  in.fixed_value = {0.0, 0.0, 0.0};
  const detail::AttaliCost cost(0.5, 0.4);
  const detail::Candidate c = cost.best(cost.prepare(in));
  EXPECT_EQ(c.position[0], 0.0);
  EXPECT_NEAR(c.position[2], 2.0, 1e-9);
}

TEST(AttaliCost, DegeneratePatchCollapsesToTheMidpointForFree) {
  detail::CostInputs in;
  in.a = {1, 1, 1};
  in.b = {1, 1, 1.5};
  const detail::AttaliCost cost(0.5, 0.4);
  const detail::Candidate c = cost.best(cost.prepare(in));
  EXPECT_DOUBLE_EQ(c.position[2], 1.25);
  EXPECT_EQ(c.cost, 0.0);
}

TEST(AttaliCost, VolumePlaneMinimiserSatisfiesTheOptimalityConditions) {
  // With alpha = 0 and W_c = 1 the combined quadric is H itself. On the plane n.(c - m) = k the
  // minimiser has M c + b parallel to n (Lagrange), whatever path computed it.
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    detail::CostInputs in;
    in.a = {20 + u(rng), 30 + u(rng), 40 + u(rng)};
    in.b = {20 + u(rng), 30 + u(rng), 40 + u(rng)};
    double total = 0.0;
    for (int p = 0; p < 6; ++p) {
      Vec3 n{u(rng), u(rng), u(rng)};
      n = (1.0 / detail::norm(n)) * n;
      const Vec3 on{20 + 3 * u(rng), 30 + 3 * u(rng), 40 + 3 * u(rng)};
      const double w = 0.5 + std::abs(u(rng));
      in.shape.add_plane(n, -detail::dot(n, on), w);
      total += w;
    }
    in.shape = in.shape.scaled(1.0 / total);
    in.weight = 1.0;
    in.isotropy.area = 1.0;
    in.isotropy.s = in.a;
    in.isotropy.q = detail::dot(in.a, in.a);
    in.preserve_volume = true;
    in.volume_normal = {u(rng), u(rng), u(rng)};
    in.volume_offset = 0.3 * u(rng);
    const bool fixed = trial % 2 == 1; // odd trials: z fixed (the general path), even: the fast path
    if (fixed) {
      in.fixed_axes = 4u;
      in.fixed_value = {0.0, 0.0, 40.0};
    }
    const detail::AttaliCost cost(1.0, 0.0);
    const auto prepared = cost.prepare(in);
    const detail::Candidate c = cost.best(prepared);
    if (c.fallback) continue; // far minimiser: a fallback position, not the optimum
    const Vec3 mid = 0.5 * detail::operator+(in.a, in.b);
    EXPECT_NEAR(detail::dot(in.volume_normal, detail::operator-(c.position, mid)), in.volume_offset, 1e-7);
    // Gradient of c^T H c (homogeneous) over 2: rows of H applied to (c, 1).
    Vec3 g{};
    for (int i = 0; i < 3; ++i)
      g[static_cast<std::size_t>(i)] = prepared.combined.at(i, 0) * c.position[0] +
                                       prepared.combined.at(i, 1) * c.position[1] +
                                       prepared.combined.at(i, 2) * c.position[2] + prepared.combined.at(i, 3);
    if (fixed) {
      EXPECT_EQ(c.position[2], 40.0);
      g[2] = 0.0;
      Vec3 n = in.volume_normal;
      n[2] = 0.0;
      EXPECT_LT(std::abs(g[0] * n[1] - g[1] * n[0]), 1e-7 * (1.0 + detail::norm(g)) * detail::norm(n)) << trial;
    } else {
      const Vec3 x = detail::cross(g, in.volume_normal);
      EXPECT_LT(detail::norm(x), 1e-7 * (1.0 + detail::norm(g)) * detail::norm(in.volume_normal)) << trial;
    }
  }
}

TEST(SolveSymmetric, PseudoInverseOfSingularSystemsStaysNearTheReference) {
  // rank 1: only the first coordinate is determined.
  const double m[9] = {2, 0, 0, 0, 0, 0, 0, 0, 0};
  const double r[3] = {4, 0, 0};
  const double ref[3] = {7, -3, 5};
  double y[3];
  detail::solve_symmetric(3, m, r, ref, y);
  EXPECT_NEAR(y[0], 2.0, 1e-12);
  EXPECT_NEAR(y[1], -3.0, 1e-12);
  EXPECT_NEAR(y[2], 5.0, 1e-12);
  // Regular 2 x 2 and 3 x 3 systems are solved exactly.
  const double m2[4] = {4, 1, 1, 3};
  const double r2[2] = {1, 2};
  detail::solve_symmetric(2, m2, r2, ref, y);
  EXPECT_NEAR(4 * y[0] + y[1], 1.0, 1e-12);
  EXPECT_NEAR(y[0] + 3 * y[1], 2.0, 1e-12);
  const double m3[9] = {4, 1, 0, 1, 3, 1, 0, 1, 2};
  const double r3[3] = {1, -2, 3};
  detail::solve_symmetric(3, m3, r3, ref, y);
  EXPECT_NEAR(4 * y[0] + y[1], 1.0, 1e-12);
  EXPECT_NEAR(y[0] + 3 * y[1] + y[2], -2.0, 1e-12);
  EXPECT_NEAR(y[1] + 2 * y[2], 3.0, 1e-12);
}

// ------------------------------------------------------------------------------------- id map

TEST(IdMap, FindsInsertsAndSwapsLikeAMap) {
  detail::IdMap map;
  std::map<std::uint64_t, std::int32_t> reference;
  std::mt19937_64 rng(3);
  for (int i = 0; i < 50000; ++i) {
    const std::uint64_t id = 3 * (rng() % 100000) + rng() % 3;
    map.insert(id, i);
    reference[id] = i;
  }
  EXPECT_EQ(map.size(), reference.size());
  for (const auto& [id, v] : reference)
    ASSERT_EQ(map.find(id), v);
  EXPECT_EQ(map.find(1ull << 60), -1);
  detail::IdMap other;
  other.swap(map);
  EXPECT_TRUE(map.empty());
  EXPECT_EQ(other.find(reference.begin()->first), reference.begin()->second);
  other.clear();
  EXPECT_EQ(other.find(reference.begin()->first), -1);
}

// ------------------------------------------------------------------------------------- components

TEST(ComponentTable, UnionKeepsTheSmallestKeyAndSumsWaitingEdges) {
  detail::ComponentTable t;
  const auto a = t.create(50, 0), b = t.create(20, 1), c = t.create(70, 2);
  t.add_waiting(a, 1);
  t.add_waiting(b, 2);
  const auto ab = t.unite(a, b);
  EXPECT_EQ(t.at(ab).key, 20u);
  EXPECT_EQ(t.at(ab).waiting, 3);
  EXPECT_EQ(t.alive_count(), 2u);
  EXPECT_EQ(t.find(b), t.find(a));
  (void)t.take_maybe_finished();
  t.add_waiting(b, -3); // the merged component has no waiting edge any more
  const auto finished = t.take_maybe_finished();
  ASSERT_EQ(finished.size(), 1u);
  EXPECT_EQ(t.find(finished[0]), t.find(a));
  // Compaction keeps live roots only and maps every old id to its root's new id.
  t.remove(t.find(c));
  const auto map = t.compact();
  EXPECT_EQ(t.record_count(), 1u);
  EXPECT_EQ(map[static_cast<std::size_t>(a)], 0);
  EXPECT_EQ(map[static_cast<std::size_t>(b)], 0);
  EXPECT_EQ(map[static_cast<std::size_t>(c)], -1);
  EXPECT_EQ(t.at(0).key, 20u);
}

} // namespace
} // namespace geotandem::tandem
