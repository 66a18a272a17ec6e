// The report's body views on meshes built from formulas: decimation within the triangle budget
// that keeps the shape, footprints as convex hulls, the map's elements, azimuth colours.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "geotandem/workflow/report.hpp"
#include "geotandem/workflow/report_views.hpp"

using namespace geotandem;
using namespace geotandem::workflow;

namespace {

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
    ++n;
  return n;
}

// A closed UV sphere of radius r (metres, and z in ms at the same numbers) at (cx, cy, cz).
mesh::SurfaceMesh sphere(double cx, double cy, double cz, double r, int rings, int segments) {
  mesh::SurfaceMesh m;
  m.points.push_back({cx, cy, cz - r});
  for (int a = 1; a < rings; ++a) {
    const double phi = std::numbers::pi * a / rings;
    for (int b = 0; b < segments; ++b) {
      const double theta = 2 * std::numbers::pi * b / segments;
      m.points.push_back(
          {cx + r * std::sin(phi) * std::cos(theta), cy + r * std::sin(phi) * std::sin(theta), cz - r * std::cos(phi)});
    }
  }
  m.points.push_back({cx, cy, cz + r});
  const auto ring = [&](int a, int b) { return static_cast<std::uint32_t>(1 + (a - 1) * segments + b % segments); };
  const auto last = static_cast<std::uint32_t>(m.points.size() - 1);
  for (int b = 0; b < segments; ++b) {
    m.triangles.push_back({0, ring(1, b + 1), ring(1, b)});
    m.triangles.push_back({last, ring(rings - 1, b), ring(rings - 1, b + 1)});
    for (int a = 1; a + 1 < rings; ++a) {
      m.triangles.push_back({ring(a, b), ring(a, b + 1), ring(a + 1, b)});
      m.triangles.push_back({ring(a + 1, b), ring(a, b + 1), ring(a + 1, b + 1)});
    }
  }
  return m;
}

double polygon_area(const std::vector<std::array<double, 2>>& p) {
  double a = 0.0;
  for (std::size_t n = 0; n < p.size(); ++n) {
    const auto &u = p[n], &v = p[(n + 1) % p.size()];
    a += u[0] * v[1] - v[0] * u[1];
  }
  return a / 2.0;
}

TEST(ReportViews, DecimationStaysWithinTheBudgetAndKeepsTheShape) {
  const double cx = 501000, cy = 6702000, cz = 900, r = 300;
  const mesh::SurfaceMesh world = sphere(cx, cy, cz, r, 120, 160); // 38080 triangles
  ASSERT_GT(world.triangle_count(), 30000u);
  const std::array<double, 2> origin{500000, 6700000};
  ReportComponent c{42, 1.1e8, 33.0, 0.1, world.triangle_count(), true, true};
  for (std::size_t budget : {4000u, 600u}) {
    const ReportBody b = display_body(c, world, origin, 1.0, budget);
    EXPECT_EQ(b.key, 42u);
    EXPECT_EQ(b.full_triangles, world.triangle_count());
    EXPECT_LE(b.triangles.size(), budget);
    EXPECT_GT(b.triangles.size(), budget / 4) << "decimated far below the budget: the shape is lost";
    EXPECT_LE(b.points.size(), b.triangles.size()) << "a closed surface has about half as many points as triangles";
    // Every point stays near the sphere (cluster means sit inside by at most a cell's sagitta).
    for (const auto& p : b.points) {
      const double d =
          std::sqrt(std::pow(p[0] + origin[0] - cx, 2) + std::pow(p[1] + origin[1] - cy, 2) + std::pow(p[2] - cz, 2));
      ASSERT_NEAR(d, r, 0.08 * r) << "budget " << budget;
    }
    for (const auto& t : b.triangles)
      for (auto v : t)
        ASSERT_LT(v, b.points.size());
  }
  // Within the budget already: drawn as it is.
  const ReportBody whole = display_body(c, world, origin, 1.0, 50000);
  EXPECT_EQ(whole.triangles.size(), world.triangle_count());
  // The footprint is the full-resolution outline: a circle of radius r, counter-clockwise.
  const ReportBody b = display_body(c, world, origin, 1.0, 600);
  EXPECT_NEAR(polygon_area(b.footprint), std::numbers::pi * r * r, 0.01 * std::numbers::pi * r * r);
}

TEST(ReportViews, ConvexHullDropsInteriorAndCollinearPoints) {
  const auto hull = convex_hull({{0, 0}, {2, 0}, {1, 0}, {2, 2}, {0, 2}, {1, 1}, {0.5, 1.5}, {2, 1}});
  ASSERT_EQ(hull.size(), 4u);
  EXPECT_DOUBLE_EQ(polygon_area(hull), 4.0);
  EXPECT_EQ(convex_hull({{1, 1}, {1, 1}}).size(), 1u);
}

TEST(ReportViews, SurveyOutlineFollowsTheAffine) {
  volume::Geometry g;
  g.shape = {11, 21, 31};
  g.affine = {1000, 10, -5, 2000, 5, 10};
  g.z0 = 100;
  g.dz = 4;
  const ReportSurvey s = survey_outline(g);
  ASSERT_TRUE(s.known);
  EXPECT_EQ(s.corners[0], (std::array<double, 2>{1000, 2000}));
  EXPECT_EQ(s.corners[2], (std::array<double, 2>{1000 + 100 - 100, 2000 + 50 + 200}));
  EXPECT_EQ(s.z_min, 100);
  EXPECT_EQ(s.z_max, 220);
  EXPECT_EQ(s.z_unit, "ms");
  EXPECT_GT(display_z_scale(s), 0.0);
}

TEST(ReportViews, AxialAzimuthsShareTheirColour) {
  EXPECT_EQ(azimuth_colour(0.0), azimuth_colour(180.0));
  EXPECT_EQ(azimuth_colour(10.0), azimuth_colour(190.0));
  EXPECT_NE(azimuth_colour(0.0), azimuth_colour(90.0));
  EXPECT_NE(azimuth_colour(45.0), azimuth_colour(135.0));
  EXPECT_EQ(azimuth_colour(37.0).size(), 7u);
}

TEST(ReportViews, MapShowsOutlineFootprintsNorthArrowAndScaleBar) {
  volume::Geometry g;
  g.shape = {101, 81, 50};
  const ReportSurvey s = survey_outline(g); // 2500 m x 2000 m, 25 m bins
  std::vector<ReportBody> bodies(3);
  for (std::size_t n = 0; n < bodies.size(); ++n) {
    bodies[n].key = 10 + n;
    bodies[n].azimuth = 60.0 * static_cast<double>(n);
    bodies[n].footprint = {{100.0 + 500 * n, 100}, {300.0 + 500 * n, 100}, {300.0 + 500 * n, 400}};
  }
  bodies[2].footprint = {{2000, 1500}}; // a single point: still shown
  const std::string svg = svg_body_map(s, bodies);
  EXPECT_EQ(count_of(svg, "class=\"survey\""), 1u);
  EXPECT_EQ(count_of(svg, "class=\"footprint\""), 3u);
  for (std::size_t n = 0; n < bodies.size(); ++n) {
    EXPECT_NE(svg.find("data-key=\"" + std::to_string(10 + n) + "\""), std::string::npos);
    EXPECT_NE(svg.find("fill=\"" + azimuth_colour(bodies[n].azimuth) + "\""), std::string::npos);
  }
  EXPECT_EQ(count_of(svg, "class=\"north-arrow\""), 1u);
  EXPECT_NE(svg.find(">N</text>"), std::string::npos);
  // A quarter of a 2.5 km wide map: a 500 m bar.
  EXPECT_NE(svg.find("class=\"scale-bar\""), std::string::npos);
  EXPECT_NE(svg.find(">500 m</text>"), std::string::npos) << svg;
}

TEST(ReportViews, PageWithoutBodyViewsWhenTheSurveyIsUnknown) {
  ReportData d;
  const std::string html = render_report(d);
  EXPECT_EQ(html.find("<h2>Bodies</h2>"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
}

} // namespace
