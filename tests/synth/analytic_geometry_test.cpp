// The analytic field's isosurface is the planted geometry as the ground truth describes it in
// world coordinates: an independent membership test built from the truth alone (centre, azimuth,
// dimensions, survey affine) must agree with {value >= iso} at every sample, and the principal axes
// of the voxel components, taken in world metres, must point along the announced azimuths.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

#include "synth_test_support.hpp"
#include "voxel_components.hpp"

namespace geotandem::synth {
namespace {

using test::dimension;

// Position of sample (i, j, k) relative to a body: s along its azimuth, n 90 degrees clockwise
// from it (both in body-frame units: metres / body_frame_unit_m), dk in samples.
struct Local {
  double s, n, dk;
};

Local local(const GroundTruth& t, const Body& b, std::int64_t i, std::int64_t j, std::int64_t k) {
  const auto w = t.geometry.world(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k));
  const double dx = w[0] - b.centre_world[0], dy = w[1] - b.centre_world[1];
  const double th = b.azimuth_deg * std::numbers::pi / 180.0;
  return {(dx * std::sin(th) + dy * std::cos(th)) / t.body_frame_unit_m,
          (dx * std::cos(th) - dy * std::sin(th)) / t.body_frame_unit_m, static_cast<double>(k) - b.centre_index[2]};
}

// Inside the body? nullopt when the sample is too close to the surface to tell.
std::optional<bool> inside(const Body& b, const Local& p) {
  if (b.type == BodyType::ellipsoid || b.type == BodyType::shell) {
    const double a = dimension(b, "semi_axis_a"), bb = dimension(b, "semi_axis_b"), c = dimension(b, "semi_axis_c");
    const double rho = std::sqrt(p.s * p.s / (a * a) + p.n * p.n / (bb * bb) + p.dk * p.dk / (c * c));
    if (std::abs(rho - 1.0) < 2e-3) return std::nullopt;
    if (b.type == BodyType::ellipsoid) return rho < 1.0;
    const double inner = dimension(b, "inner_scale");
    if (std::abs(rho / inner - 1.0) < 2e-3) return std::nullopt;
    return rho < 1.0 && rho > inner;
  }
  // Tube: the centre line is h(t) = A sin(k t + phase) across the axis through C, and the body's
  // centre is the line's point at t = 0, so C lies A sin(phase) across from it. Nearest point by
  // brute force: a scan of the only parameters that can be nearest, then golden-section search.
  const double amp = dimension(b, "amplitude"), wn = 2.0 * std::numbers::pi / dimension(b, "wavelength");
  const double phase = dimension(b, "phase"), r = dimension(b, "radius"), hl = dimension(b, "half_length");
  const double n = p.n + amp * std::sin(phase);
  auto dist2 = [&](double t) {
    const double dn = n - amp * std::sin(wn * t + phase), ds = p.s - t;
    return ds * ds + dn * dn + p.dk * p.dk;
  };
  const double reach = std::sqrt(dist2(p.s)); // the nearest point is no farther than c(s)
  if (std::abs(n) > amp + r + 1.0 || std::abs(p.dk) > r + 1.0) return false;
  double best = p.s, best_d2 = dist2(p.s);
  for (double t = p.s - reach; t <= p.s + reach; t += 0.05)
    if (dist2(t) < best_d2) {
      best_d2 = dist2(t);
      best = t;
    }
  double lo = best - 0.05, hi = best + 0.05;
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int it = 0; it < 60; ++it) {
    const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
    (dist2(m1) < dist2(m2) ? hi : lo) = dist2(m1) < dist2(m2) ? m2 : m1;
  }
  const double t = 0.5 * (lo + hi), d = std::sqrt(dist2(t));
  if (std::abs(d - r) < 0.01 || std::abs(std::abs(t) - hl) < 0.05) return std::nullopt;
  return d < r && std::abs(t) < hl;
}

struct Survey {
  std::uint64_t seed;
  double bin_inline, bin_crossline, rotation;
};

class AnalyticGeometry : public ::testing::TestWithParam<Survey> {
protected:
  std::unique_ptr<SyntheticCube> make() const {
    AnalyticOptions o;
    o.shape = {72, 64, 48};
    o.seed = GetParam().seed;
    o.survey.bin_inline_m = GetParam().bin_inline;
    o.survey.bin_crossline_m = GetParam().bin_crossline;
    o.survey.rotation_deg = GetParam().rotation;
    return make_analytic(o);
  }
};

TEST_P(AnalyticGeometry, IsosurfaceIsThePlantedSurface) {
  auto cube = make();
  const auto& truth = cube->truth();
  const auto box = cube->geometry().bounds();
  const auto values = cube->read(box);
  for (const auto& body : truth.bodies) {
    std::size_t checked = 0, in = 0, wrong = 0;
    for (auto i = std::max<std::int64_t>(0, std::lround(std::floor(body.bounds_lo[0])));
         i <= std::min<std::int64_t>(box.hi[0] - 1, std::lround(std::ceil(body.bounds_hi[0]))); ++i)
      for (auto j = std::max<std::int64_t>(0, std::lround(std::floor(body.bounds_lo[1])));
           j <= std::min<std::int64_t>(box.hi[1] - 1, std::lround(std::ceil(body.bounds_hi[1]))); ++j)
        for (auto k = std::max<std::int64_t>(0, std::lround(std::floor(body.bounds_lo[2])));
             k <= std::min<std::int64_t>(box.hi[2] - 1, std::lround(std::ceil(body.bounds_hi[2]))); ++k) {
          const auto expected = inside(body, local(truth, body, i, j, k));
          if (!expected) continue;
          ++checked;
          in += *expected;
          if (*expected != (values[box.offset({i, j, k})] >= 0.5f) && ++wrong <= 3)
            ADD_FAILURE() << body.name << ": sample (" << i << ", " << j << ", " << k << ") should be "
                          << (*expected ? "inside" : "outside") << ", value " << values[box.offset({i, j, k})];
        }
    EXPECT_EQ(wrong, 0u) << body.name;
    EXPECT_GT(checked, 0u);
    if (!body.cut_by_border) {
      EXPECT_GT(static_cast<double>(in), 0.7 * body.volume_voxels) << body.name;
    }
  }
}

TEST_P(AnalyticGeometry, AzimuthsAndCentresGoThroughTheSurveyAffine) {
  auto cube = make();
  const auto& truth = cube->truth();
  const auto& g = truth.geometry;
  const auto values = cube->read(g.bounds());
  const auto components = testing::voxel_components(values, g.shape, 0.5f);
  int measured = 0;
  for (const auto& body : truth.bodies) {
    const auto w = g.world(body.centre_index[0], body.centre_index[1], body.centre_index[2]);
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(w[a], body.centre_world[a], 1e-6) << body.name;
    if (body.type != BodyType::ellipsoid || body.cut_by_border) continue;
    const testing::VoxelComponent* c = nullptr;
    for (const auto& candidate : components)
      if (test::inside_bounds(candidate, body) && candidate.voxels > 20) c = &candidate;
    ASSERT_NE(c, nullptr) << body.name;
    const auto centroid = c->centroid();
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(centroid[a], body.centre_index[a], 0.35) << body.name << " axis " << a;
    // Horizontal covariance in world metres: C_w = A C A^T with A the affine's linear part.
    const auto cov = c->covariance();
    const double m[2][2] = {{g.affine.xi, g.affine.xj}, {g.affine.yi, g.affine.yj}};
    const double ci[2][2] = {{cov[0], cov[1]}, {cov[1], cov[3]}};
    double cw[2][2] = {};
    for (int r = 0; r < 2; ++r)
      for (int s = 0; s < 2; ++s)
        for (int u = 0; u < 2; ++u)
          for (int v = 0; v < 2; ++v)
            cw[r][s] += m[r][u] * ci[u][v] * m[s][v];
    // Major axis angle from east, counter-clockwise; azimuth is from north, clockwise.
    const double from_east = 0.5 * std::atan2(2.0 * cw[0][1], cw[0][0] - cw[1][1]) * 180.0 / std::numbers::pi;
    EXPECT_LE(test::axial_difference(90.0 - from_east, body.azimuth_deg), 3.0) << body.name;
    ++measured;
  }
  EXPECT_GE(measured, 2);
}

INSTANTIATE_TEST_SUITE_P(Surveys, AnalyticGeometry,
                         ::testing::Values(Survey{1, 25.0, 25.0, 30.0}, Survey{2, 12.5, 25.0, 30.0},
                                           Survey{3, 40.0, 20.0, -65.0}, Survey{4, 25.0, 12.5, 115.0},
                                           Survey{5, 6.25, 25.0, 45.0}));

} // namespace
} // namespace geotandem::synth
