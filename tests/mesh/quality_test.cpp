// Triangle shape measures (seed section 4), area and volume.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>
#include <random>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/quality.hpp"
#include "mesh_fixtures.hpp"

namespace geotandem::mesh {
namespace {

using namespace fixtures;

// The definition, computed the long way: eigenvalues of M_t = 1/3 sum (v - t^)(v - t^)^T.
double aspect_ratio_by_eigen(const Point& a, const Point& b, const Point& c) {
  const Eigen::Vector3d va(a[0], a[1], a[2]), vb(b[0], b[1], b[2]), vc(c[0], c[1], c[2]);
  const Eigen::Vector3d g = (va + vb + vc) / 3.0;
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& v : {va, vb, vc})
    m += (v - g) * (v - g).transpose() / 3.0;
  const Eigen::Vector3d l = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvalues(); // ascending
  return std::sqrt(std::max(0.0, l[1]) / l[2]);
}

// A flat patch of equilateral triangles (a triangular lattice), `n` by `n` rhombi.
SurfaceMesh equilateral_patch(int n, double side) {
  SurfaceMesh s;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      s.points.push_back({side * (i + 0.5 * j), side * j * std::sqrt(3.0) / 2.0, 0.0});
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
      s.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return s;
}

TEST(Quality, AspectRatioOfSpecialTriangles) {
  const double h = std::sqrt(3.0) / 2.0;
  EXPECT_NEAR(aspect_ratio({0, 0, 0}, {1, 0, 0}, {0.5, h, 0}), 1.0, 1e-12);
  // Any scale, place and orientation.
  EXPECT_NEAR(aspect_ratio({1e5, 2e6, 30}, {1e5, 2e6 + 7, 30}, {1e5 + 7 * h, 2e6 + 3.5, 30}), 1.0, 1e-9);
  EXPECT_NEAR(aspect_ratio({0, 0, 0}, {0, 1e-3, 0}, {0, 0.5e-3, 1e-3 * h}), 1.0, 1e-9);
  EXPECT_NEAR(aspect_ratio({0, 0, 0}, {1, 0, 0}, {2, 0, 0}), 0.0, 1e-12); // collinear
  EXPECT_EQ(aspect_ratio({3, 3, 3}, {3, 3, 3}, {3, 3, 3}), 0.0);          // a point
  EXPECT_LT(aspect_ratio({0, 0, 0}, {1, 0, 0}, {0.5, 1e-4, 0}), 1e-3);    // sliver
  EXPECT_LT(aspect_ratio({0, 0, 0}, {1, 0, 0}, {1e-4, 1e-4, 0}), 1e-3);   // needle
}

TEST(Quality, AspectRatioMatchesTheEigenDefinition) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int n = 0; n < 500; ++n) {
    const Point a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
    const double rho = aspect_ratio(a, b, c);
    EXPECT_NEAR(rho, aspect_ratio_by_eigen(a, b, c), 1e-7);
    EXPECT_GE(rho, 0.0);
    EXPECT_LE(rho, 1.0);
    EXPECT_NEAR(rho, aspect_ratio(b, c, a), 1e-12); // corner order does not matter
    EXPECT_NEAR(rho, aspect_ratio(a, c, b), 1e-12);
  }
}

TEST(Quality, AnisotropyOfEquilateralAndSliverMeshes) {
  const SurfaceMesh regular = equilateral_patch(12, 2.5);
  EXPECT_NEAR(anisotropy(regular), 0.0, 1e-12);
  EXPECT_EQ(small_angle_share(regular), 0.0);

  SurfaceMesh slivers = regular;
  for (Point& p : slivers.points)
    p[1] *= 1e-4; // squashed flat
  EXPECT_GT(anisotropy(slivers), 0.999);
  EXPECT_EQ(small_angle_share(slivers), 1.0);

  // Half the triangles squashed: the anisotropy is the mean of the two.
  const SurfaceMesh both = merged(regular, slivers);
  EXPECT_NEAR(anisotropy(both), 0.5 * anisotropy(slivers), 1e-12);
  EXPECT_NEAR(small_angle_share(both), 0.5, 1e-12);

  EXPECT_EQ(anisotropy(SurfaceMesh{}), 0.0);
  EXPECT_EQ(small_angle_share(SurfaceMesh{}), 0.0);
}

TEST(Quality, SmallAngleShareFollowsTheThreshold) {
  // Right triangles with a 20 degree corner.
  SurfaceMesh s;
  const double t = std::tan(20.0 * std::numbers::pi / 180.0);
  s.points = {{0, 0, 0}, {1, 0, 0}, {1, t, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0.5, 1}};
  s.triangles = {{0, 1, 2}, {3, 4, 5}}; // 20 and ~26.6 degrees
  EXPECT_EQ(small_angle_share(s, 10.0), 0.0);
  EXPECT_EQ(small_angle_share(s, 20.5), 0.5);
  EXPECT_EQ(small_angle_share(s, 27.0), 1.0);
  s.triangles.push_back({0, 0, 1}); // zero angle
  EXPECT_NEAR(small_angle_share(s, 1.0), 1.0 / 3.0, 1e-12);
}

TEST(Quality, IcosphereTriangles) {
  // The icosahedron is exactly equilateral; refining and projecting distorts its triangles a
  // little (rho drops fast: an isosceles triangle 13 % flatter than equilateral has rho 0.87).
  EXPECT_NEAR(anisotropy(icosphere(0, 5.0)), 0.0, 1e-12);
  const SurfaceMesh s = icosphere(4);
  EXPECT_GT(anisotropy(s), 0.01);
  EXPECT_LT(anisotropy(s), 0.2);
  EXPECT_EQ(small_angle_share(s, 40.0), 0.0);
}

TEST(Quality, VolumeSignFollowsOrientation) {
  SurfaceMesh s = torus(4.0, 1.0, 60, 30);
  const double v = enclosed_volume(s);
  EXPECT_GT(v, 0.0);
  for (Triangle& t : s.triangles)
    std::swap(t[0], t[1]);
  EXPECT_NEAR(enclosed_volume(s), -v, 1e-9 * v);
  // Translation does not change a closed surface's volume.
  for (Point& p : s.points)
    p = {p[0] + 3e5, p[1] - 6e6, p[2] + 2e3};
  EXPECT_NEAR(enclosed_volume(s), -v, 1e-7 * v);
}

TEST(Quality, RejectsBadIndices) {
  SurfaceMesh s = icosphere(0);
  s.triangles.push_back({0, 1, 99});
  EXPECT_THROW(anisotropy(s), InvalidArgument);
  EXPECT_THROW(surface_area(s), InvalidArgument);
  EXPECT_THROW(enclosed_volume(s), InvalidArgument);
  EXPECT_THROW(small_angle_share(s), InvalidArgument);
}

} // namespace
} // namespace geotandem::mesh
