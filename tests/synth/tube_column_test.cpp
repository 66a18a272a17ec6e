// The analytic kind computes a tube's distance a column of samples at a time (the part that
// depends on x and y once per column, shapes.hpp): it must give the bits of the point-by-point
// formula at every sample, near the tube, at its ends and far from it.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "hash.hpp"
#include "shapes.hpp"

namespace geotandem::synth::detail {
namespace {

TEST(TubeColumn, ColumnByColumnGivesTheBitsOfPointByPoint) {
  LayoutRng rng(20261202);
  std::size_t near = 0, checked = 0;
  for (int trial = 0; trial < 40; ++trial) {
    Tube t;
    t.radius = rng.uniform(2.0, 6.0);
    t.band = 1.5;
    t.reach = 3.0;
    const double wavelength = rng.uniform(36.0, 64.0);
    t.line.centre = {rng.uniform(-50.0, 50.0), rng.uniform(-50.0, 50.0), rng.uniform(10.0, 40.0)};
    t.line.azimuth = rng.uniform(0.0, 2.0 * std::numbers::pi);
    t.line.axes = Axes::of(t.line.azimuth);
    t.line.half_length = rng.uniform(8.0, 35.0);
    t.line.wavenumber = 2.0 * std::numbers::pi / wavelength;
    t.line.amplitude = rng.uniform(0.6, 1.0) * SinuousLine::max_amplitude(wavelength, t.radius + t.band + 1.0);
    t.line.phase = rng.uniform(0.0, 2.0 * std::numbers::pi);
    t.line.prepare();
    for (int column = 0; column < 200; ++column) {
      // Columns over the tube's box and beyond it, at whole and fractional positions.
      const double x = t.line.centre.x + rng.uniform(-45.0, 45.0), y = t.line.centre.y + rng.uniform(-45.0, 45.0);
      Tube::Column c = t.column({x, y, 0.0});
      for (int k = 0; k < 60; ++k) {
        const double z = k * 0.75;
        const double want = t.signed_distance(Vec3{x, y, z});
        const double got = t.signed_distance(c, z);
        ASSERT_EQ(std::memcmp(&got, &want, sizeof got), 0) << "trial " << trial << ", column (" << x << ", " << y
                                                           << "), z " << z << ": " << got << " against " << want;
        near += want > -t.band;
        ++checked;
      }
    }
  }
  EXPECT_GT(near, 2000u) << "too few samples near the tubes to test the exact branch (of " << checked << ")";
}

} // namespace
} // namespace geotandem::synth::detail
