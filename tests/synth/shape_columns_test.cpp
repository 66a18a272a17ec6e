// The analytic kind computes every shape's distance a column of samples at a time (the part that
// depends on x and y once per column, shapes.hpp): it must give the bits of the point-by-point
// formulas the generator used before (written out below) at every sample, near the shapes, at a
// tube's ends, in a shell's cavity and far away, so that its cubes keep their bytes.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include "hash.hpp"
#include "shapes.hpp"

namespace geotandem::synth::detail {
namespace {

// The point-by-point formulas, each sum in its order.
double ellipsoid_distance(const Ellipsoid& e, const Vec3& p) {
  const double dx = p.x - e.centre.x, dy = p.y - e.centre.y;
  const double s = (dx * e.axes.ux + dy * e.axes.uy) / e.a;
  const double n = (dx * e.axes.vx + dy * e.axes.vy) / e.b;
  const double z = (p.z - e.centre.z) / e.c;
  const double rho = std::sqrt(s * s + n * n + z * z);
  const double g = std::sqrt(s * s / (e.a * e.a) + n * n / (e.b * e.b) + z * z / (e.c * e.c));
  if (g == 0.0) return std::min({e.a, e.b, e.c});
  return (1.0 - rho) * rho / g;
}

double point_distance(const Ellipsoid& e, const Vec3& p) {
  return ellipsoid_distance(e, p);
}

double point_distance(const Shell& shell, const Vec3& p) {
  return std::min(ellipsoid_distance(shell.outer, p), -ellipsoid_distance(shell.cavity, p));
}

double point_distance(const Sphere& sphere, const Vec3& p) {
  const double dx = p.x - sphere.centre.x, dy = p.y - sphere.centre.y, dz = p.z - sphere.centre.z;
  return sphere.r - std::sqrt(dx * dx + dy * dy + dz * dz);
}

double point_distance(const Tube& t, const Vec3& p) {
  double s = 0.0, n = 0.0;
  t.line.local(p, s, n);
  const double dz = p.z - t.line.centre.z;
  const double near = t.radius + t.band;
  if (std::abs(dz) > near || std::abs(n) > t.line.amplitude + near ||
      std::abs(s) > t.line.half_length + t.radius + t.reach)
    return -t.reach;
  const double across = std::abs(n - t.line.offset(s)) * t.line.lipschitz_factor;
  if (across * across + dz * dz > near * near) return -t.reach;
  const double u = t.line.nearest(s, n);
  const double ds = s - u, dn = n - t.line.offset(u);
  const double d = std::sqrt(ds * ds + dn * dn + dz * dz);
  return std::min(t.radius - d, t.line.end_distance(s, n));
}

struct Counts {
  std::size_t near = 0, checked = 0;
};

// Compares both forms over 200 random columns around `centre`, 60 samples each.
template <class Shape>
void expect_same_bits(const Shape& shape, const Vec3& centre, double band, LayoutRng& rng, Counts& counts) {
  for (int column = 0; column < 200; ++column) {
    const double x = centre.x + rng.uniform(-45.0, 45.0), y = centre.y + rng.uniform(-45.0, 45.0);
    auto c = shape.column({x, y, 0.0});
    for (int k = 0; k < 60; ++k) {
      const double z = k * 0.75;
      const double want = point_distance(shape, Vec3{x, y, z});
      const double got = shape.signed_distance(c, z);
      ASSERT_EQ(std::memcmp(&got, &want, sizeof got), 0)
          << "column (" << x << ", " << y << "), z " << z << ": " << got << " against " << want;
      counts.near += want > -band;
      ++counts.checked;
    }
  }
}

TEST(ShapeColumns, ColumnByColumnGivesTheBitsOfPointByPoint) {
  LayoutRng rng(20261202);
  Counts tubes, ellipsoids, shells, spheres;
  for (int trial = 0; trial < 40; ++trial) {
    const Vec3 centre{rng.uniform(-50.0, 50.0), rng.uniform(-50.0, 50.0), rng.uniform(10.0, 40.0)};
    const double azimuth = rng.uniform(0.0, 2.0 * std::numbers::pi);

    Tube t;
    t.radius = rng.uniform(2.0, 6.0);
    t.band = 1.5;
    t.reach = 3.0;
    const double wavelength = rng.uniform(36.0, 64.0);
    t.line.centre = centre;
    t.line.azimuth = azimuth;
    t.line.axes = Axes::of(azimuth);
    t.line.half_length = rng.uniform(8.0, 35.0);
    t.line.wavenumber = 2.0 * std::numbers::pi / wavelength;
    t.line.amplitude = rng.uniform(0.6, 1.0) * SinuousLine::max_amplitude(wavelength, t.radius + t.band + 1.0);
    t.line.phase = rng.uniform(0.0, 2.0 * std::numbers::pi);
    t.line.prepare();
    expect_same_bits(t, centre, t.band, rng, tubes);

    const Ellipsoid e(centre, rng.uniform(8.0, 30.0), rng.uniform(4.0, 20.0), rng.uniform(3.0, 12.0), azimuth);
    expect_same_bits(e, centre, 1.5, rng, ellipsoids);
    expect_same_bits(Shell(e, rng.uniform(0.3, 0.7)), centre, 1.5, rng, shells);
    expect_same_bits(Sphere{centre, rng.uniform(1.0, 3.0)}, centre, 1.5, rng, spheres);
    if (HasFatalFailure()) return;
  }
  // Enough samples near each kind of surface to test the exact branches, not only the far ones.
  EXPECT_GT(tubes.near, 2000u) << "of " << tubes.checked;
  EXPECT_GT(ellipsoids.near, 2000u) << "of " << ellipsoids.checked;
  EXPECT_GT(shells.near, 2000u) << "of " << shells.checked;
  EXPECT_GT(spheres.near, 100u) << "of " << spheres.checked;
}

} // namespace
} // namespace geotandem::synth::detail
