// one_sided_distance and hausdorff_distance against exact answers and a brute-force oracle.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/quality.hpp"
#include "mesh_fixtures.hpp"

namespace geotandem::mesh {
namespace {

using namespace fixtures;

// A probe: a triangle so small that its distance to anything is the distance from p, within 1e-9.
SurfaceMesh probe(const Point& p) {
  SurfaceMesh s;
  s.points = {p, {p[0] + 1e-10, p[1], p[2]}, {p[0], p[1] + 1e-10, p[2]}};
  s.triangles = {{0, 1, 2}};
  return s;
}

double distance_to(const Point& p, const SurfaceMesh& to) {
  return one_sided_distance(probe(p), to, 0).max;
}

// Oracle: the nearest of a dense barycentric sampling of every triangle (no grid, no projection):
// an upper bound on the true distance, never above it by more than the sampling step.
double sampled_distance(const Point& p, const SurfaceMesh& to, int steps) {
  double best = std::numeric_limits<double>::infinity();
  for (const Triangle& t : to.triangles) {
    const Point &a = to.points[t[0]], &b = to.points[t[1]], &c = to.points[t[2]];
    for (int i = 0; i <= steps; ++i)
      for (int j = 0; i + j <= steps; ++j) {
        const double u = static_cast<double>(i) / steps, v = static_cast<double>(j) / steps;
        double d2 = 0.0;
        for (int k = 0; k < 3; ++k) {
          const double x = a[k] + u * (b[k] - a[k]) + v * (c[k] - a[k]) - p[k];
          d2 += x * x;
        }
        best = std::min(best, d2);
      }
  }
  return std::sqrt(best);
}

double longest_edge(const SurfaceMesh& s) {
  double e = 0.0;
  for (const Triangle& t : s.triangles)
    for (int k = 0; k < 3; ++k) {
      const Point &a = s.points[t[k]], &b = s.points[t[(k + 1) % 3]];
      e = std::max(e, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
    }
  return e;
}

TEST(Distance, ExactAgainstOneTriangle) {
  SurfaceMesh tri;
  tri.points = {{0, 0, 0}, {4, 0, 0}, {0, 3, 0}};
  tri.triangles = {{0, 1, 2}};
  EXPECT_NEAR(distance_to({1, 1, 2.5}, tri), 2.5, 1e-9);      // above the inside
  EXPECT_NEAR(distance_to({1, 1, -0.5}, tri), 0.5, 1e-9);     // below
  EXPECT_NEAR(distance_to({-3, -4, 0}, tri), 5.0, 1e-9);      // nearest to a corner
  EXPECT_NEAR(distance_to({2, -2, 0}, tri), 2.0, 1e-9);       // nearest to an edge
  EXPECT_NEAR(distance_to({4, 3, 0}, tri), 12.0 / 5.0, 1e-9); // beyond the hypotenuse (3x + 4y = 12)
  EXPECT_NEAR(distance_to({1, 1, 0}, tri), 0.0, 1e-9);
  // Degenerate targets: a segment and a point.
  SurfaceMesh seg;
  seg.points = {{0, 0, 0}, {2, 0, 0}, {1, 0, 0}};
  seg.triangles = {{0, 1, 2}};
  EXPECT_NEAR(distance_to({1, 3, 4}, seg), 5.0, 1e-9);
  EXPECT_NEAR(distance_to({5, 4, 0}, seg), 5.0, 1e-9);
  SurfaceMesh dot;
  dot.points = {{1, 1, 1}};
  dot.triangles = {{0, 0, 0}};
  EXPECT_NEAR(distance_to({1, 4, 5}, dot), 5.0, 1e-9);
}

TEST(Distance, GridSearchMatchesBruteForce) {
  // A bumpy torus and points inside, near and far outside its bounding box.
  SurfaceMesh s = torus(6.0, 2.0, 30, 15);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> bump(-0.3, 0.3);
  for (Point& p : s.points)
    p = {p[0] + bump(rng), p[1] + bump(rng), p[2] + bump(rng)};
  const int steps = 12;
  const double step = longest_edge(s) / steps;
  std::uniform_real_distribution<double> u(-12, 12);
  for (int n = 0; n < 45; ++n) {
    const double spread = n < 15 ? 1.0 : (n < 30 ? 2.0 : 8.0);
    const Point p{spread * u(rng), spread * u(rng), spread * u(rng) / 3};
    const double d = distance_to(p, s);
    const double oracle = sampled_distance(p, s, steps);
    EXPECT_LE(d, oracle + 1e-9) << "at " << p[0] << " " << p[1] << " " << p[2];
    EXPECT_GE(d, oracle - step) << "at " << p[0] << " " << p[1] << " " << p[2];
  }
}

TEST(Distance, SurfaceToItselfIsZero) {
  const SurfaceMesh s = torus(5.0, 1.0, 32, 16);
  const DistanceStats d = hausdorff_distance(s, s, 4);
  EXPECT_NEAR(d.max, 0.0, 1e-12);
  EXPECT_NEAR(d.rms, 0.0, 1e-12);
  EXPECT_NEAR(d.mean, 0.0, 1e-12);
  EXPECT_EQ(d.samples, 2 * (s.points.size() + 4 * s.triangles.size()));
}

TEST(Distance, ConcentricSpheresAreTheRadiusDifferenceApart) {
  const SurfaceMesh inner = icosphere(3, 1.0, {3, 2, 1});
  const SurfaceMesh outer = icosphere(3, 1.25, {3, 2, 1});
  // Inscribed polyhedra: points lie at most a sagitta inside their sphere.
  const double sagitta = 0.01;
  const DistanceStats out = one_sided_distance(inner, outer, 1);
  const DistanceStats in = one_sided_distance(outer, inner, 1);
  EXPECT_NEAR(out.max, 0.25, sagitta);
  EXPECT_NEAR(in.max, 0.25, sagitta);
  EXPECT_NEAR(out.mean, 0.25, sagitta);
  EXPECT_NEAR(in.rms, 0.25, sagitta);
  EXPECT_LE(out.mean, out.rms + 1e-15);
  EXPECT_LE(out.rms, out.max + 1e-15);
  EXPECT_EQ(out.samples, inner.points.size() + inner.triangles.size());
  const DistanceStats both = hausdorff_distance(inner, outer, 1);
  EXPECT_EQ(both.max, std::max(out.max, in.max));
  EXPECT_EQ(both.samples, out.samples + in.samples);
  EXPECT_NEAR(both.mean, (out.mean * out.samples + in.mean * in.samples) / both.samples, 1e-12);
}

TEST(Distance, ParallelDiscsAreTheirGapApart) {
  const SurfaceMesh low = disc(10.0, 6, 24, 0.0);
  const SurfaceMesh high = disc(10.0, 6, 24, 0.75);
  const DistanceStats d = hausdorff_distance(low, high, 5);
  EXPECT_NEAR(d.max, 0.75, 1e-12);
  EXPECT_NEAR(d.mean, 0.75, 1e-12);
  EXPECT_NEAR(d.rms, 0.75, 1e-12);
}

TEST(Distance, SamplesLieOnTheSurface) {
  // Any sample of a surface is at distance 0 from the same surface under another numbering.
  const SurfaceMesh s = icosphere(2, 2.0);
  SurfaceMesh r = s;
  std::reverse(r.triangles.begin(), r.triangles.end());
  EXPECT_NEAR(one_sided_distance(s, r, 9).max, 0.0, 1e-12);
}

TEST(Distance, EdgeCases) {
  const SurfaceMesh s = icosphere(1);
  EXPECT_EQ(one_sided_distance(SurfaceMesh{}, s).samples, 0u);
  EXPECT_THROW(one_sided_distance(s, SurfaceMesh{}), InvalidArgument);
  EXPECT_THROW(hausdorff_distance(s, SurfaceMesh{}), InvalidArgument);
  EXPECT_THROW(one_sided_distance(s, s, -1), InvalidArgument);
  EXPECT_EQ(one_sided_distance(s, s, 0).samples, s.points.size());
  SurfaceMesh bad = s;
  bad.points[5][1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(one_sided_distance(bad, s), DataError);
  EXPECT_THROW(one_sided_distance(s, bad), DataError);
}

} // namespace
} // namespace geotandem::mesh
