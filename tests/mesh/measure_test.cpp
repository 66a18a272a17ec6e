// to_world and measure_component: volumes, areas, centroids, boxes, azimuth, dip, elongation,
// closed and cut flags, through square, rotated, non-square and mirrored survey affines.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/measure.hpp"
#include "geotandem/mesh/quality.hpp"
#include "geotandem/mesh/topology.hpp"
#include "mesh_fixtures.hpp"

namespace geotandem::mesh {
namespace {

using namespace fixtures;
constexpr double pi = std::numbers::pi;

volume::Geometry cube(volume::SurveyAffine affine, double dz = 4.0, double z0 = 0.0) {
  volume::Geometry g;
  g.shape = {400, 400, 400};
  g.affine = affine;
  g.dz = dz;
  g.z0 = z0;
  return g;
}

// Inline direction at `azimuth_deg` with bins of `di` metres, crossline direction `skew_deg`
// further clockwise with bins of `dj` metres. With x east and y north, a crossline direction
// clockwise from the inline one (skew in (0, 180)) makes xi*yj - xj*yi negative: a mirror map.
volume::SurveyAffine rotated(double azimuth_deg, double di, double dj, double skew_deg = 90.0) {
  const double a = azimuth_deg * pi / 180.0, b = (azimuth_deg + skew_deg) * pi / 180.0;
  volume::SurveyAffine f;
  f.x0 = 612345.0;
  f.y0 = 6543210.0;
  f.xi = di * std::sin(a);
  f.yi = di * std::cos(a);
  f.xj = dj * std::sin(b);
  f.yj = dj * std::cos(b);
  return f;
}

double determinant(const volume::Geometry& g) {
  return (g.affine.xi * g.affine.yj - g.affine.xj * g.affine.yi) * g.dz;
}

// The inverse of to_world, written independently: solves the 2x2 affine for (i, j), and keeps the
// surface outward in index space.
SurfaceMesh to_index(const SurfaceMesh& world, const volume::Geometry& g) {
  const auto& f = g.affine;
  const double det = f.xi * f.yj - f.xj * f.yi;
  SurfaceMesh s = world;
  for (Point& p : s.points) {
    const double x = p[0] - f.x0, y = p[1] - f.y0;
    p = {(f.yj * x - f.xj * y) / det, (-f.yi * x + f.xi * y) / det, (p[2] - g.z0) / g.dz};
  }
  if (determinant(g) < 0)
    for (Triangle& t : s.triangles)
      std::swap(t[1], t[2]);
  return s;
}

TEST(Measure, IcosphereVolumeAndAreaConvergeAtSecondOrder) {
  const double r = 3.0;
  const double volume = 4.0 / 3.0 * pi * r * r * r, area = 4.0 * pi * r * r;
  double last_dv = 0.0, last_da = 0.0;
  for (int level = 1; level <= 6; ++level) {
    const SurfaceMesh s = icosphere(level, r, {7, -2, 5});
    const double dv = volume - enclosed_volume(s), da = area - surface_area(s);
    EXPECT_GT(dv, 0.0); // inscribed: always a little smaller
    EXPECT_GT(da, 0.0);
    if (level > 1) {
      EXPECT_GT(last_dv / dv, 3.5) << "level " << level; // halving edges divides the error by ~4
      EXPECT_GT(last_da / da, 3.5) << "level " << level;
    }
    last_dv = dv;
    last_da = da;
  }
  EXPECT_LT(last_dv / volume, 1e-3);
  EXPECT_LT(last_da / area, 1e-3);
}

TEST(Measure, BoxVolumeIsExactFarFromTheOrigin) {
  const Point lo{612345.25, 6543210.5, 1500.0};
  const SurfaceMesh s = box(lo, {lo[0] + 300.0, lo[1] + 200.0, lo[2] + 10.0});
  EXPECT_NEAR(enclosed_volume(s), 300.0 * 200.0 * 10.0, 1e-6);
  EXPECT_NEAR(surface_area(s), 2.0 * (300.0 * 200.0 + 300.0 * 10.0 + 200.0 * 10.0), 1e-6);
}

TEST(Measure, TorusVolumeAndArea) {
  const double R = 5.0, r = 1.5;
  const SurfaceMesh s = torus(R, r, 240, 120);
  EXPECT_NEAR(enclosed_volume(s), 2.0 * pi * pi * R * r * r, 2e-3 * 2.0 * pi * pi * R * r * r);
  EXPECT_NEAR(surface_area(s), 4.0 * pi * pi * R * r, 2e-3 * 4.0 * pi * pi * R * r);
}

TEST(Measure, ToWorldScalesVolumeByTheDeterminant) {
  const SurfaceMesh index = icosphere(3, 10.0, {50, 60, 70});
  const double index_volume = enclosed_volume(index);
  ASSERT_GT(index_volume, 0.0);
  for (const auto& affine : {rotated(0, 25, 25), rotated(33, 12.5, 30), rotated(33, 12.5, 30, -90),
                             rotated(-70, 20, 15, 75), rotated(120, 20, 15, -110)}) {
    const volume::Geometry g = cube(affine, 4.0, 800.0);
    const SurfaceMesh world = to_world(index, g);
    ASSERT_EQ(world.points.size(), index.points.size());
    for (std::size_t v = 0; v < index.points.size(); v += 37) {
      const auto w = g.world(index.points[v][0], index.points[v][1], index.points[v][2]);
      EXPECT_EQ(world.points[v], (Point{w[0], w[1], w[2]}));
    }
    const double expected = index_volume * std::abs(determinant(g));
    EXPECT_NEAR(enclosed_volume(world), expected, 1e-9 * expected) << "det " << determinant(g);
    const ComponentStats stats = measure_component(index, g);
    EXPECT_NEAR(stats.volume, expected, 1e-9 * expected);
    EXPECT_TRUE(check_topology(world).is_closed_manifold());
  }
}

TEST(Measure, MirroredAffineKeepsVolumePositive) {
  const SurfaceMesh index = box({10, 20, 30}, {14, 23, 32});
  const volume::Geometry g = cube(rotated(10, 25, 25, 90), 2.0);
  ASSERT_LT(determinant(g), 0.0);
  const ComponentStats stats = measure_component(index, g);
  EXPECT_NEAR(stats.volume, 4.0 * 3.0 * 2.0 * 25.0 * 25.0 * 2.0, 1e-6);
  EXPECT_NEAR(stats.area, 2.0 * (100.0 * 75.0 + 100.0 * 4.0 + 75.0 * 4.0), 1e-6);
}

TEST(Measure, SphereStats) {
  volume::SurveyAffine f;
  f.x0 = 1000;
  f.y0 = 2000;
  f.xi = 10;
  f.yj = 20; // non-square, axis aligned
  const volume::Geometry g = cube(f, 5.0, 100.0);
  const double r = 8.0;
  const SurfaceMesh index = icosphere(4, r, {50, 60, 70});
  const ComponentStats s = measure_component(index, g);
  EXPECT_EQ(s.vertex_count, index.points.size());
  EXPECT_EQ(s.triangle_count, index.triangles.size());
  EXPECT_TRUE(s.closed);
  EXPECT_FALSE(s.cut_by_border);
  // The world body is an ellipsoid with semi-axes 80, 160, 40.
  const double a = 10 * r, b = 20 * r, c = 5 * r;
  EXPECT_NEAR(s.volume, 4.0 / 3.0 * pi * a * b * c, 3e-3 * 4.0 / 3.0 * pi * a * b * c);
  const Point center{1000 + 10 * 50, 2000 + 20 * 60, 100 + 5 * 70};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(s.centroid[k], center[k], 1e-6);
    EXPECT_NEAR(s.obb_center[k], center[k], 1e-6 * b);
  }
  const Point half{a, b, c};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(s.box_min[k], center[k] - half[k], 1e-9 * b);
    EXPECT_NEAR(s.box_max[k], center[k] + half[k], 1e-9 * b);
  }
  // Longest axis north (y), then east, then down; half extents are the semi-axes.
  EXPECT_NEAR(std::abs(s.obb_axes[0][1]), 1.0, 1e-9);
  EXPECT_NEAR(std::abs(s.obb_axes[1][0]), 1.0, 1e-9);
  EXPECT_NEAR(std::abs(s.obb_axes[2][2]), 1.0, 1e-9);
  EXPECT_NEAR(s.obb_half_extents[0], b, 1e-9 * b);
  EXPECT_NEAR(s.obb_half_extents[1], a, 1e-9 * b);
  EXPECT_NEAR(s.obb_half_extents[2], c, 1e-9 * b);
  EXPECT_NEAR(axial_difference_deg(s.azimuth, 0.0), 0.0, 1e-6);
  EXPECT_NEAR(s.dip, 0.0, 1e-6);
  EXPECT_GT(s.elongation, 0.3);
  EXPECT_LT(s.elongation, 0.7);
}

TEST(Measure, HemisphereCentroidIsHalfwayUp) {
  // Archimedes: the centroid of a hemispherical shell lies at r / 2 above its rim.
  volume::SurveyAffine f;
  f.xi = 1;
  f.yj = 1;
  const volume::Geometry g = cube(f, 1.0);
  const double r = 10.0;
  SurfaceMesh s = hemisphere(r, 60, 120);
  for (Point& p : s.points)
    p = {p[0] + 50, p[1] + 50, p[2] + 20};
  const ComponentStats stats = measure_component(s, g);
  EXPECT_FALSE(stats.closed);
  EXPECT_FALSE(stats.cut_by_border);
  EXPECT_EQ(stats.volume, 0.0);
  EXPECT_NEAR(stats.centroid[0], 50.0, 1e-9);
  EXPECT_NEAR(stats.centroid[1], 50.0, 1e-9);
  EXPECT_NEAR(stats.centroid[2], 20.0 + r / 2, 2e-3 * r);
  EXPECT_NEAR(stats.area, 2.0 * pi * r * r, 2e-3 * 2.0 * pi * r * r);
}

TEST(Measure, CutByTheBorderOnEachOuterPlane) {
  const volume::Geometry g = cube(rotated(20, 12.5, 25));
  const double last = static_cast<double>(g.shape[0] - 1); // the cube is 400 on every axis
  const SurfaceMesh cap = hemisphere(6.0, 8, 16);
  // The rim (z = 0 of the fixture) placed on a given plane, the cap towards the inside.
  auto place = [&](int axis, bool high) {
    SurfaceMesh s = cap;
    for (Point& p : s.points) {
      Point q{};
      q[(axis + 1) % 3] = 100 + p[0];
      q[(axis + 2) % 3] = 120 + p[1];
      q[axis] = high ? last - p[2] : p[2];
      p = q;
    }
    return s;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (bool high : {false, true}) {
      const ComponentStats s = measure_component(place(axis, high), g);
      EXPECT_TRUE(s.cut_by_border) << "axis " << axis << (high ? " high" : " low");
      EXPECT_FALSE(s.closed);
      EXPECT_EQ(s.volume, 0.0);
    }
  // The same cap one sample inside is not cut.
  SurfaceMesh inside = place(2, false);
  for (Point& p : inside.points)
    p[2] += 1.0;
  EXPECT_FALSE(measure_component(inside, g).cut_by_border);
  // A closed body with a corner on a face reaches that face (marching cubes puts a vertex on an
  // outer plane only where the body does; a simplified cap may have lost every cap triangle): it is
  // cut there, and measured as the closed solid it is.
  const ComponentStats touching = measure_component(icosphere(2, 5.0, {5, 50, 50}), g);
  EXPECT_EQ(touching.cut_faces, 0x01); // i-
  EXPECT_TRUE(touching.closed);
  EXPECT_GT(touching.volume, 0.0);
  EXPECT_EQ(touching.cap_area, 0.0);
  // One sample inside, it is not.
  EXPECT_FALSE(measure_component(icosphere(2, 5.0, {6, 50, 50}), g).cut_by_border);
}

TEST(Measure, AzimuthOfAnElongatedBodyThroughAnyAffine) {
  // Long axis 400 m, width 100 m, height 60 (depth units); rotated to a known world azimuth,
  // then brought to index space through each affine and measured back.
  const SurfaceMesh unit = icosphere(3);
  for (const auto& affine :
       {rotated(0, 25, 25), rotated(37, 12.5, 30), rotated(37, 12.5, 30, -90), rotated(-50, 25, 12.5, 70)}) {
    const volume::Geometry g = cube(affine, 4.0, 500.0);
    const auto c = g.world(200, 200, 200);
    for (double az : {0.0, 30.0, 90.0, 135.0, 179.0}) {
      const SurfaceMesh world = transformed(unit, {100, 400, 60}, az, 0.0, {c[0], c[1], c[2]});
      const ComponentStats s = measure_component(to_index(world, g), g);
      EXPECT_LT(axial_difference_deg(s.azimuth, az), 0.5) << "azimuth " << az << " measured " << s.azimuth;
      EXPECT_GE(s.azimuth, 0.0);
      EXPECT_LT(s.azimuth, 180.0);
      EXPECT_NEAR(s.volume, 4.0 / 3.0 * pi * 100 * 400 * 60, 0.03 * 4.0 / 3.0 * pi * 100 * 400 * 60);
      EXPECT_GT(s.elongation, 0.5);
      EXPECT_LE(s.elongation, 1.0);
      EXPECT_NEAR(s.dip, 0.0, 0.5);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(s.centroid[k], c[k], 1e-6 * 400);
    }
  }
}

TEST(Measure, ElongationGrowsWithTheAspectOfTheFootprint) {
  const SurfaceMesh unit = icosphere(3);
  const volume::Geometry g = cube(rotated(15, 25, 25));
  double last = -1.0;
  for (double ratio : {1.0, 1.5, 3.0, 10.0}) {
    const SurfaceMesh world = transformed(unit, {100, 100 * ratio, 50}, 40, 0, {1e4, 2e4, 400});
    const double e = measure_component(to_index(world, g), g).elongation;
    if (ratio == 1.0) {
      EXPECT_LT(e, 0.02);
    }
    EXPECT_GT(e, last);
    last = e;
  }
  EXPECT_GT(last, 0.8);
}

TEST(Measure, DipOfATiltedBodyInADepthCube) {
  const SurfaceMesh unit = icosphere(3);
  volume::Geometry g = cube(rotated(25, 12.5, 25), 5.0, 1000.0);
  g.z_unit = volume::SampleUnit::metres;
  for (double dip : {0.0, 30.0, 60.0, 90.0}) {
    const SurfaceMesh world = transformed(unit, {60, 400, 40}, 60.0, dip, {5e5, 6e6, 2000});
    const ComponentStats s = measure_component(to_index(world, g), g);
    EXPECT_NEAR(s.dip, dip, 0.5) << "dip " << dip;
    if (dip < 80) {
      EXPECT_LT(axial_difference_deg(s.azimuth, 60.0), 0.5) << "dip " << dip;
    }
    EXPECT_NEAR(s.obb_half_extents[0], 400, 0.02 * 400);
  }
}

TEST(Measure, RejectsEmptySurfacesAndBadGeometry) {
  const volume::Geometry g = cube(rotated(0, 25, 25));
  EXPECT_THROW(measure_component(SurfaceMesh{}, g), InvalidArgument);
  volume::Geometry flat = g;
  flat.affine.xj = flat.affine.xi;
  flat.affine.yj = flat.affine.yi;
  EXPECT_THROW(measure_component(icosphere(1, 1, {5, 5, 5}), flat), InvalidArgument);
  EXPECT_THROW(to_world(icosphere(1), flat), InvalidArgument);
}

TEST(Axial, MeanByAngleDoubling) {
  EXPECT_NEAR(axial_difference_deg(axial_mean_deg({170, 10}), 0.0), 0.0, 1e-9);
  EXPECT_NEAR(axial_mean_deg({30, 50}), 40.0, 1e-9);
  EXPECT_NEAR(axial_mean_deg({30, 50 + 180}), 40.0, 1e-9);
  EXPECT_NEAR(axial_mean_deg({175, 15}), 5.0, 1e-9);
  EXPECT_NEAR(axial_mean_deg({10, 40}, {1, 0}), 10.0, 1e-9);
  EXPECT_NEAR(axial_mean_deg({120}), 120.0, 1e-9);
  EXPECT_NEAR(axial_mean_deg({-30}), 150.0, 1e-9);
  const double m = axial_mean_deg({0, 60, 61, 62});
  EXPECT_GE(m, 0.0);
  EXPECT_LT(m, 180.0);
  EXPECT_THROW(axial_mean_deg({1, 2}, {1}), InvalidArgument);
}

TEST(Axial, Difference) {
  EXPECT_NEAR(axial_difference_deg(179, 1), 2.0, 1e-12);
  EXPECT_NEAR(axial_difference_deg(1, 179), 2.0, 1e-12);
  EXPECT_NEAR(axial_difference_deg(10, 190), 0.0, 1e-12);
  EXPECT_NEAR(axial_difference_deg(0, 90), 90.0, 1e-12);
  EXPECT_NEAR(axial_difference_deg(-20, 20), 40.0, 1e-12);
  EXPECT_NEAR(axial_difference_deg(45, 170), 55.0, 1e-12);
}

} // namespace
} // namespace geotandem::mesh
