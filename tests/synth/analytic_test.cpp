// The analytic kind against an independent oracle: 6-connected voxel components of
// {value >= iso} must be exactly the planted bodies plus the bubbles, with the analytic volumes.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "synth_test_support.hpp"
#include "voxel_components.hpp"

namespace geotandem::synth {
namespace {

using testing::VoxelComponent;

struct Matched {
  std::vector<std::vector<const VoxelComponent*>> per_body;
  std::vector<const VoxelComponent*> bubbles;
};

// Assigns every component to the body whose bounds hold it; components held by none are bubbles.
Matched match(const GroundTruth& truth, const std::vector<VoxelComponent>& components) {
  Matched m;
  m.per_body.resize(truth.bodies.size());
  for (const auto& c : components) {
    int holders = 0;
    for (std::size_t b = 0; b < truth.bodies.size(); ++b)
      if (test::inside_bounds(c, truth.bodies[b])) {
        m.per_body[b].push_back(&c);
        ++holders;
      }
    EXPECT_LE(holders, 1) << "a component lies in the bounds of two bodies: bodies are not separated";
    if (holders == 0) m.bubbles.push_back(&c);
  }
  return m;
}

// Knud Thomsen's approximation of an ellipsoid's area (relative error below 1.1 %).
double ellipsoid_area(double a, double b, double c) {
  const double p = 1.6075;
  return 4.0 * std::numbers::pi *
         std::pow((std::pow(a * b, p) + std::pow(a * c, p) + std::pow(b * c, p)) / 3.0, 1.0 / p);
}

double surface_area(const Body& body) {
  using test::dimension;
  switch (body.type) {
  case BodyType::tube: {
    const double r = dimension(body, "radius");
    return 2.0 * std::numbers::pi * r * dimension(body, "arc_length") + 2.0 * std::numbers::pi * r * r;
  }
  case BodyType::shell: {
    const double s = dimension(body, "inner_scale");
    return ellipsoid_area(dimension(body, "semi_axis_a"), dimension(body, "semi_axis_b"),
                          dimension(body, "semi_axis_c")) *
           (1.0 + s * s);
  }
  default:
    return ellipsoid_area(dimension(body, "semi_axis_a"), dimension(body, "semi_axis_b"),
                          dimension(body, "semi_axis_c"));
  }
}

struct Config {
  volume::Index3 shape;
  std::uint64_t seed;
  double bin_inline, bin_crossline, rotation;
};

AnalyticOptions options_of(const Config& c) {
  AnalyticOptions o;
  o.shape = c.shape;
  o.seed = c.seed;
  o.survey.bin_inline_m = c.bin_inline;
  o.survey.bin_crossline_m = c.bin_crossline;
  o.survey.rotation_deg = c.rotation;
  return o;
}

class AnalyticComponents : public ::testing::TestWithParam<Config> {};

TEST_P(AnalyticComponents, AreThePlantedBodiesPlusTheBubbles) {
  auto cube = make_analytic(options_of(GetParam()));
  const auto& truth = cube->truth();
  const auto values = cube->read(cube->geometry().bounds());
  const auto components = testing::voxel_components(values, truth.geometry.shape, static_cast<float>(*truth.iso));

  EXPECT_EQ(components.size(), truth.bodies.size() + truth.bubble_count);
  const Matched m = match(truth, components);
  for (std::size_t b = 0; b < truth.bodies.size(); ++b) {
    // A body cut by the border still shows as one piece: its centre is inside the cube.
    ASSERT_EQ(m.per_body[b].size(), 1u) << truth.bodies[b].name;
    EXPECT_GT(static_cast<double>(m.per_body[b][0]->voxels), 5.0 * truth.bubble_volume_threshold_voxels)
        << truth.bodies[b].name;
    EXPECT_EQ(m.per_body[b][0]->touches_border(truth.geometry.shape), truth.bodies[b].cut_by_border)
        << truth.bodies[b].name;
  }
  ASSERT_EQ(m.bubbles.size(), truth.bubble_count);
  const double bubble_max = 4.0 / 3.0 * std::numbers::pi * std::pow(truth.bubble_radius_max, 3);
  EXPECT_LT(bubble_max, truth.bubble_volume_threshold_voxels);
  for (const auto* c : m.bubbles) {
    EXPECT_LT(static_cast<double>(c->voxels), truth.bubble_volume_threshold_voxels);
    EXPECT_FALSE(c->touches_border(truth.geometry.shape));
  }
}

INSTANTIATE_TEST_SUITE_P(Surveys, AnalyticComponents,
                         ::testing::Values(Config{{40, 40, 40}, 1, 25.0, 25.0, 30.0},
                                           Config{{40, 40, 40}, 2, 25.0, 25.0, 30.0},
                                           Config{{64, 48, 40}, 3, 12.5, 25.0, 30.0},
                                           Config{{72, 56, 48}, 4, 40.0, 20.0, -65.0},
                                           Config{{96, 80, 64}, 5, 25.0, 25.0, 0.0},
                                           Config{{80, 64, 48}, 6, 6.25, 25.0, 10.0}, // the most elongated bins
                                           Config{{64, 80, 48}, 7, 50.0, 12.5, 200.0}));

// Volumes against voxel counts. The count differs from the volume only through the samples whose
// cell is cut by the surface (about sqrt(3) S of them for a surface of area S, each off by less
// than one); and moving a surface by d samples changes its count by about d S. So the error over
// the area is the mean distance between the voxelised and the analytic surface. Per body we allow
// a quarter of a sample (the worst of 400 bodies in 30 seeds was 0.12: coherent errors along tubes
// parallel to the lattice); summed over all closed bodies of a type, where errors of opposite
// signs cancel, 0.03 of a sample (the worst of five 6-cube groups was 0.008). A tube measured by
// its straight length instead of its arc length, or an ellipsoid off by 3 % in volume, fails.
TEST(AnalyticCube, VolumesMatchVoxelCounts) {
  std::map<BodyType, std::pair<double, double>> sums; // type -> (sum of errors, sum of areas)
  int closed = 0;
  for (std::uint64_t seed = 11; seed <= 16; ++seed) {
    AnalyticOptions options;
    options.shape = {96, 80, 64};
    options.seed = seed;
    auto cube = make_analytic(options);
    const auto& truth = cube->truth();
    const auto values = cube->read(cube->geometry().bounds());
    const auto components = testing::voxel_components(values, truth.geometry.shape, 0.5f);
    const Matched m = match(truth, components);
    for (std::size_t b = 0; b < truth.bodies.size(); ++b) {
      const Body& body = truth.bodies[b];
      ASSERT_EQ(m.per_body[b].size(), 1u) << body.name;
      EXPECT_NEAR(body.volume_world, body.volume_voxels * truth.voxel_volume_world, 1e-9 * body.volume_world);
      if (body.cut_by_border) continue;
      ++closed;
      const double area = surface_area(body);
      const double error = static_cast<double>(m.per_body[b][0]->voxels) - body.volume_voxels;
      EXPECT_LE(std::abs(error), 0.25 * area) << body.name << " seed " << seed << ": " << m.per_body[b][0]->voxels
                                              << " samples, analytic volume " << body.volume_voxels;
      auto& s = sums[body.type == BodyType::shell ? BodyType::ellipsoid : body.type];
      s.first += error;
      s.second += area;
    }
  }
  EXPECT_GT(closed, 40);
  for (const auto& [type, s] : sums)
    EXPECT_LE(std::abs(s.first / s.second), 0.03) << to_string(type) << ": summed error " << s.first;
}

TEST(AnalyticCube, ShellHasACavity) {
  for (std::uint64_t seed : {1u, 7u}) {
    AnalyticOptions options;
    options.shape = {64, 56, 48};
    options.seed = seed;
    auto cube = make_analytic(options);
    int shells = 0;
    for (const auto& body : cube->truth().bodies) {
      if (body.type != BodyType::shell) continue;
      ++shells;
      EXPECT_TRUE(body.has_cavity);
      const volume::Index3 centre{std::lround(body.centre_index[0]), std::lround(body.centre_index[1]),
                                  std::lround(body.centre_index[2])};
      const float at_centre = cube->read(volume::Box{centre, {centre[0] + 1, centre[1] + 1, centre[2] + 1}})[0];
      EXPECT_LT(at_centre, 0.5f) << "the centre of " << body.name << " should be in its cavity";
      // The wall along the vertical axis: inside, outside, inside, outside going up from the centre.
      const double c = test::dimension(body, "semi_axis_c"), inner = test::dimension(body, "inner_scale");
      auto value_at = [&](double dk) {
        const volume::Index3 at{centre[0], centre[1], std::lround(body.centre_index[2] + dk)};
        return cube->read(volume::Box{at, {at[0] + 1, at[1] + 1, at[2] + 1}})[0];
      };
      EXPECT_GE(value_at(0.5 * (1.0 + inner) * c), 0.5f) << body.name << " wall";
      EXPECT_LT(value_at(c + 2.0), 0.5f) << body.name << " outside";
    }
    EXPECT_EQ(shells, 1);
  }
}

TEST(AnalyticCube, EveryCubeHasTheSpecialBodies) {
  for (const volume::Index3& shape :
       {volume::Index3{40, 40, 40}, volume::Index3{40, 64, 48}, volume::Index3{128, 96, 64}})
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      AnalyticOptions options;
      options.shape = shape;
      options.seed = seed;
      auto cube = make_analytic(options);
      const auto& truth = cube->truth();
      int cavity = 0, cut = 0, tubes = 0, centre = 0, quarter = 0;
      for (const auto& b : truth.bodies) {
        cavity += b.has_cavity;
        cut += b.cut_by_border;
        tubes += b.type == BodyType::tube;
        bool all_mid = true, crosses = false;
        for (int a = 0; a < 3; ++a) {
          const double mid = static_cast<double>(shape[a] / 2);
          all_mid = all_mid && b.bounds_lo[a] < mid && b.bounds_hi[a] > mid;
          for (auto p : truth.block_planes[a])
            crosses = crosses || (b.bounds_lo[a] < static_cast<double>(p) && b.bounds_hi[a] > static_cast<double>(p));
        }
        EXPECT_EQ(crosses, b.crosses_block_plane) << b.name;
        const double q1 = static_cast<double>(shape[0] / 4), q3 = static_cast<double>(shape[0] * 3 / 4);
        quarter += b.type == BodyType::tube &&
                   ((b.bounds_lo[0] < q1 && b.bounds_hi[0] > q1) || (b.bounds_lo[0] < q3 && b.bounds_hi[0] > q3));
        centre += all_mid;
        // Cut bodies leave the cube; closed ones keep two samples from every face.
        bool outside = false, near_face = false, margin = true;
        for (int a = 0; a < 3; ++a) {
          const double last = static_cast<double>(shape[a] - 1);
          outside = outside || b.bounds_lo[a] < 0.0 || b.bounds_hi[a] > last;
          near_face = near_face || b.bounds_lo[a] < 1.0 || b.bounds_hi[a] > last - 1.0;
          margin = margin && b.bounds_lo[a] >= 2.0 && b.bounds_hi[a] <= last - 2.0;
        }
        EXPECT_EQ(b.cut_by_border, near_face) << b.name;
        EXPECT_TRUE(b.cut_by_border ? outside : margin) << b.name;
      }
      EXPECT_EQ(cavity, 1) << "seed " << seed;
      EXPECT_GE(cut, 1) << "seed " << seed;
      EXPECT_GE(tubes, 1) << "seed " << seed;
      EXPECT_GE(centre, 1) << "seed " << seed << ": no body across the three mid-planes";
      EXPECT_GE(quarter, 1) << "seed " << seed << ": no tube across an inline quarter-plane";
    }
}

TEST(AnalyticCube, BodiesAndBubblesScaleWithTheCube) {
  AnalyticOptions small, large;
  small.shape = {64, 64, 64};
  large.shape = {256, 256, 256};
  auto a = make_analytic(small);
  auto b = make_analytic(large); // construction only: places bodies, computes no sample
  EXPECT_GT(b->truth().bubble_count, 1000u);
  EXPECT_GT(b->truth().bodies.size(), 100u);
  EXPECT_GT(b->truth().bubble_count, 20 * a->truth().bubble_count);
  EXPECT_GT(b->truth().bodies.size(), 10 * a->truth().bodies.size());
  AnalyticOptions none = small;
  none.body_density = 0.0;
  none.bubble_density = 0.0;
  auto c = make_analytic(none);
  EXPECT_EQ(c->truth().bodies.size(), 4u); // the special bodies only
  EXPECT_EQ(c->truth().bubble_count, 0u);
}

TEST(AnalyticCube, ValuesStayInTheUnitRangeAndBelowIsoAwayFromBodies) {
  AnalyticOptions options;
  options.shape = {96, 96, 64};
  options.seed = 9;
  options.body_density = 0.0; // the four special bodies only, and no bubbles
  options.bubble_density = 0.0;
  auto cube = make_analytic(options);
  const auto values = cube->read(cube->geometry().bounds());
  float lo = 1.0f, hi = 0.0f;
  for (float v : values) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  EXPECT_GE(lo, 0.0f);
  EXPECT_LE(hi, 1.0f);
  EXPECT_EQ(hi, 1.0f); // body interiors saturate
  // Samples more than 12 samples from every body's box hold the background alone, below 0.25.
  const auto box = cube->geometry().bounds();
  std::vector<char> near(values.size(), 0);
  for (const auto& b : cube->truth().bodies)
    for (auto i = std::max<std::int64_t>(0, std::lround(b.bounds_lo[0]) - 12);
         i < std::min<std::int64_t>(box.hi[0], std::lround(b.bounds_hi[0]) + 12); ++i)
      for (auto j = std::max<std::int64_t>(0, std::lround(b.bounds_lo[1]) - 12);
           j < std::min<std::int64_t>(box.hi[1], std::lround(b.bounds_hi[1]) + 12); ++j)
        for (auto k = std::max<std::int64_t>(0, std::lround(b.bounds_lo[2]) - 12);
             k < std::min<std::int64_t>(box.hi[2], std::lround(b.bounds_hi[2]) + 12); ++k)
          near[box.offset({i, j, k})] = 1;
  std::size_t far = 0;
  for (std::size_t n = 0; n < values.size(); ++n)
    if (!near[n]) {
      ++far;
      ASSERT_LT(values[n], 0.25f) << "sample " << n;
    }
  EXPECT_GT(far, values.size() / 10);
}

} // namespace
} // namespace geotandem::synth
