// Marching cubes: closed, consistently oriented 2-manifolds on smooth, noisy and degenerate fields,
// every one of the 256 corner sign patterns, volumes, and independence from the extraction axis.

#include <gtest/gtest.h>

#include <numbers>

#include "geotandem/mesh/topology.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "mc_support.hpp"

namespace geotandem::tandem {
namespace {

using namespace testing;

struct Extracted {
  mesh::SurfaceMesh surface;
  std::vector<std::uint64_t> ids;
};

Extracted extract(const volume::Volume& v, float iso, int axis = 0) {
  Extracted out;
  out.surface = extract_surface(v, cube_cells(v.geometry().shape), McOptions{iso, axis}, &out.ids);
  return out;
}

// The invariants every extraction must keep when the surface stays inside the cube.
void expect_closed(const mesh::SurfaceMesh& s, const std::string& what) {
  const mesh::TopologyReport r = mesh::check_topology(s);
  EXPECT_TRUE(r.is_closed_manifold()) << what << ": " << r.summary();
  EXPECT_EQ(r.degenerate_triangles, 0u) << what << ": " << r.summary();
  EXPECT_EQ(r.unreferenced_vertices, 0u) << what << ": " << r.summary();
}

// Shortest edge and smallest triangle area of a surface.
std::pair<double, double> smallest_edge_and_area(const mesh::SurfaceMesh& s) {
  double edge = 1e300, area = 1e300;
  for (const auto& t : s.triangles) {
    std::array<double, 3> p[3];
    for (int m = 0; m < 3; ++m)
      p[m] = s.points[t[m]];
    for (int m = 0; m < 3; ++m) {
      const auto& a = p[m];
      const auto& b = p[(m + 1) % 3];
      edge = std::min(edge, std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                                      (a[2] - b[2]) * (a[2] - b[2])));
    }
    const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double w[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const double x = u[1] * w[2] - u[2] * w[1], y = u[2] * w[0] - u[0] * w[2], z = u[0] * w[1] - u[1] * w[0];
    area = std::min(area, 0.5 * std::sqrt(x * x + y * y + z * z));
  }
  return {edge, area};
}

TEST(McTopology, SphereIsAClosedSphereWithTheRightVolume) {
  const double r = 8.0;
  auto v = field({24, 22, 23}, sphere({11.3, 10.6, 11.1}, r));
  const Extracted e = extract(*v, 0.0f);
  expect_closed(e.surface, "sphere");
  const auto report = mesh::check_topology(e.surface);
  EXPECT_EQ(report.components, 1u);
  EXPECT_EQ(report.euler_characteristic, 2);
  const double exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  EXPECT_NEAR(enclosed_volume(e.surface), exact, 0.015 * exact);
  for (const auto& p : e.surface.points) {
    const double d =
        std::sqrt((p[0] - 11.3) * (p[0] - 11.3) + (p[1] - 10.6) * (p[1] - 10.6) + (p[2] - 11.1) * (p[2] - 11.1));
    EXPECT_NEAR(d, r, 0.05);
  }
}

TEST(McTopology, CavityCountsNegative) {
  // A spherical cavity inside a block that fills the cube but its shell: the outer surface
  // counts positive, the cavity's negative (flat triangles inside a radius-5 sphere miss a few
  // percent of its volume, hence the tolerance).
  auto block = [](bool cavity) {
    return field({20, 20, 20}, [cavity](double i, double j, double k) {
      const bool shell = i == 0 || j == 0 || k == 0 || i == 19 || j == 19 || k == 19;
      const float inside = cavity ? std::min(1.0f, -sphere({9.5, 9.3, 9.6}, 5.0)(i, j, k)) : 1.0f;
      return shell ? -1.0f : inside;
    });
  };
  const Extracted full = extract(*block(false), 0.0f);
  const Extracted holed = extract(*block(true), 0.0f);
  expect_closed(holed.surface, "cavity");
  EXPECT_EQ(mesh::check_topology(holed.surface).components, 2u);
  const double cavity = 4.0 / 3.0 * std::numbers::pi * 125.0;
  EXPECT_NEAR(enclosed_volume(holed.surface), enclosed_volume(full.surface) - cavity, 0.04 * cavity);
}

TEST(McTopology, TorusHasGenusOne) {
  const double R = 7.0, r = 3.0;
  auto v = field({23, 24, 12}, torus({11.2, 11.6, 5.6}, R, r));
  const Extracted e = extract(*v, 0.0f);
  expect_closed(e.surface, "torus");
  const auto report = mesh::check_topology(e.surface);
  EXPECT_EQ(report.components, 1u);
  EXPECT_EQ(report.euler_characteristic, 0);
  const double exact = 2.0 * std::numbers::pi * std::numbers::pi * R * r * r;
  EXPECT_NEAR(enclosed_volume(e.surface), exact, 0.04 * exact); // flat triangles cut the tube's curvature
}

TEST(McTopology, RandomNoiseGivesClosedManifoldsMatchingTheVoxelOracle) {
  // Random values make every ambiguous face and cell configuration appear many times.
  for (unsigned seed = 1; seed <= 6; ++seed) {
    auto v = noise({13, 11, 12}, seed);
    const Extracted e = extract(*v, 0.0f);
    const std::string what = "noise seed " + std::to_string(seed);
    expect_closed(e.surface, what);
    EXPECT_EQ(mesh::check_topology(e.surface).components, boundary_pairs(*v, 0.0f)) << what;
    EXPECT_GT(enclosed_volume(e.surface), 0.0) << what;
  }
}

TEST(McTopology, ExactEqualitiesMakeNoZeroAreaTriangleNorZeroLengthEdge) {
  // Integer field, integer iso: a third of the samples sit exactly on the threshold.
  for (float iso : {0.0f, 1.0f, 2.0f})
    for (unsigned seed = 1; seed <= 3; ++seed) {
      auto v = noise({12, 13, 11}, seed, 3, -1.0f);
      const Extracted e = extract(*v, iso);
      const std::string what = "levels, iso " + std::to_string(iso) + " seed " + std::to_string(seed);
      ASSERT_FALSE(e.surface.empty()) << what;
      expect_closed(e.surface, what);
      EXPECT_EQ(mesh::check_topology(e.surface).components, boundary_pairs(*v, iso)) << what;
      const auto [edge, area] = smallest_edge_and_area(e.surface);
      EXPECT_GE(edge, kMcVertexMargin) << what;
      EXPECT_GT(area, 0.25 * kMcVertexMargin * kMcVertexMargin) << what;
      for (const auto& p : e.surface.points) // no vertex on a sample
        EXPECT_FALSE(p[0] == std::floor(p[0]) && p[1] == std::floor(p[1]) && p[2] == std::floor(p[2])) << what;
    }
}

// Number of 6-connected groups among the inside corners of one cell (the oracle for one case).
std::size_t corner_components(int pattern) {
  std::array<int, 8> parent{0, 1, 2, 3, 4, 5, 6, 7};
  auto find = [&](int a) {
    while (parent[a] != a)
      a = parent[a];
    return a;
  };
  for (int c = 0; c < 8; ++c)
    for (int axis = 0; axis < 3; ++axis) {
      const int d = c | (1 << axis);
      if (d != c && ((pattern >> c) & 1) && ((pattern >> d) & 1)) parent[find(c)] = find(d);
    }
  std::size_t n = 0;
  for (int c = 0; c < 8; ++c)
    n += ((pattern >> c) & 1) && find(c) == c;
  return n;
}

TEST(McTopology, EveryCornerPatternClosesInsideAnOutsideCube) {
  // Each pattern as the one 2x2x2 cell in the middle of an outside 4x4x4 cube, with unit values
  // and with random magnitudes (which move vertices and quad diagonals around).
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> magnitude(0.05f, 1.0f);
  for (int pattern = 0; pattern < 256; ++pattern)
    for (bool random : {false, true}) {
      std::vector<float> samples(64, -1.0f);
      for (int c = 0; c < 8; ++c) {
        const int i = 1 + (c & 1), j = 1 + ((c >> 1) & 1), k = 1 + ((c >> 2) & 1);
        const float m = random ? magnitude(rng) : 1.0f;
        samples[static_cast<std::size_t>((i * 4 + j) * 4 + k)] = ((pattern >> c) & 1) ? m : -m;
      }
      volume::MemoryVolume v(geometry_of({4, 4, 4}), samples);
      const std::string what = "pattern " + std::to_string(pattern) + (random ? " random" : " unit");
      std::multiset<IdTriangle> first;
      for (int axis = 0; axis < 3; ++axis) {
        const Extracted e = extract(v, 0.0f, axis);
        IdSurface ids;
        add_to(ids, e.surface, e.ids);
        if (axis == 0) first = ids.triangles;
        EXPECT_EQ(ids.triangles, first) << what << " axis " << axis;
      }
      const Extracted e = extract(v, 0.0f);
      if (pattern == 0) {
        EXPECT_TRUE(e.surface.empty());
        continue;
      }
      expect_closed(e.surface, what);
      const auto report = mesh::check_topology(e.surface);
      EXPECT_EQ(report.components, corner_components(pattern)) << what;
      EXPECT_EQ(report.euler_characteristic, 2 * static_cast<long>(report.components)) << what;
      EXPECT_GT(enclosed_volume(e.surface), 0.0) << what;
    }
}

TEST(McTopology, EveryAxisGivesTheSameSurface) {
  auto blobs = field({19, 17, 21}, [](double i, double j, double k) {
    return std::max(sphere({6.2, 7.1, 8.3}, 4.6)(i, j, k), sphere({11.4, 9.2, 12.7}, 5.1)(i, j, k));
  });
  auto rough = noise({11, 12, 13}, 42);
  for (const volume::MemoryVolume* v : {blobs.get(), rough.get()}) {
    IdSurface reference;
    double volume0 = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const Extracted e = extract(*v, 0.0f, axis);
      expect_closed(e.surface, "axis " + std::to_string(axis));
      IdSurface s;
      add_to(s, e.surface, e.ids);
      if (axis == 0) {
        reference = s;
        volume0 = enclosed_volume(e.surface);
        continue;
      }
      // The table lives in the cube's frame, so the triangle set is the same, not just close.
      EXPECT_EQ(s.triangles, reference.triangles) << "axis " << axis;
      EXPECT_EQ(s.positions, reference.positions) << "axis " << axis;
      EXPECT_NEAR(enclosed_volume(e.surface), volume0, 1e-9 * std::abs(volume0)) << "axis " << axis;
    }
  }
}

} // namespace
} // namespace geotandem::tandem
