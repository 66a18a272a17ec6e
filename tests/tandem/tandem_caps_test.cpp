// Bodies cut by the cube's border are closed by caps on its outer sample planes (docs/caps.md).
// Oracles: full-resolution marching cubes of the cube padded with one layer of a low value (below
// the iso) for volumes, the inside voxels' principal axis for azimuths. Ellipsoids cut by each of
// the six faces, by an edge and by a corner; marching cubes alone, then the tandem in 1 and many
// blocks.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "blocks_support.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/mesh/caps.hpp"
#include "geotandem/mesh/measure.hpp"
#include "geotandem/mesh/quality.hpp"
#include "geotandem/mesh/topology.hpp"
#include "geotandem/tandem/blocks.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "simplify_fixtures.hpp"
#include "voxel_components.hpp"

namespace geotandem::tandem {
namespace {

const volume::Index3 kShape{80, 72, 56};
constexpr double kPad = -1000.0; // the padding's value, far below the iso (0)

struct Case {
  std::string name;
  std::array<double, 3> centre;
  std::uint8_t faces; // the cut faces expected (bits 2 * axis + side)
};

std::vector<Case> cases() {
  return {{"i-", {6.0, 36.0, 28.0}, 0x01},
          {"i+", {73.0, 36.0, 28.0}, 0x02},
          {"j-", {40.0, 4.0, 28.0}, 0x04},
          {"j+", {40.0, 67.0, 28.0}, 0x08},
          {"k-", {40.0, 36.0, 3.0}, 0x10},
          {"k+", {40.0, 36.0, 52.5}, 0x20},
          {"edge i-j-", {6.0, 4.0, 28.0}, 0x05},
          {"corner i+j-k+", {70.0, 5.0, 50.0}, 0x26},
          {"deep corner i+j-k+", {73.0, 4.0, 52.5}, 0x26}};
}

// An ellipsoid of semi-axes 20, 10 and 8 voxels, its long axis turned 35 degrees from i towards j:
// 4 (1 - normalised radius), positive inside.
double ellipsoid(const std::array<double, 3>& c, double i, double j, double k) {
  const double t = 35.0 * std::numbers::pi / 180.0;
  const double x = i - c[0], y = j - c[1], z = k - c[2];
  const double s = std::cos(t) * x + std::sin(t) * y, n = -std::sin(t) * x + std::cos(t) * y;
  return 8.0 * (1.0 - std::sqrt((s / 20.0) * (s / 20.0) + (n / 10.0) * (n / 10.0) + (z / 8.0) * (z / 8.0)));
}

std::vector<float> samples_of(const Case& c, const volume::Index3& shape, std::int64_t pad) {
  std::vector<float> v(static_cast<std::size_t>(shape[0] * shape[1] * shape[2]));
  std::size_t n = 0;
  for (std::int64_t i = 0; i < shape[0]; ++i)
    for (std::int64_t j = 0; j < shape[1]; ++j)
      for (std::int64_t k = 0; k < shape[2]; ++k) {
        const bool outside =
            i < pad || j < pad || k < pad || i >= shape[0] - pad || j >= shape[1] - pad || k >= shape[2] - pad;
        v[n++] = static_cast<float>(outside ? kPad
                                            : ellipsoid(c.centre, static_cast<double>(i - pad),
                                                        static_cast<double>(j - pad), static_cast<double>(k - pad)));
      }
  return v;
}

std::unique_ptr<volume::MemoryVolume> cube_of(const Case& c) {
  return std::make_unique<volume::MemoryVolume>(fixtures::test_geometry(kShape), samples_of(c, kShape, 0), c.name);
}

// The oracle surface: marching cubes of the cube padded by one low sample on every side, moved
// back into the cube's index coordinates.
mesh::SurfaceMesh padded_surface(const Case& c) {
  const volume::Index3 padded{kShape[0] + 2, kShape[1] + 2, kShape[2] + 2};
  volume::MemoryVolume v(fixtures::test_geometry(padded), samples_of(c, padded, 1), c.name + " padded");
  McOptions options;
  options.caps = false;
  mesh::SurfaceMesh s = extract_surface(v, cube_cells(padded), options);
  for (auto& p : s.points)
    for (double& x : p)
      x -= 1.0;
  return s;
}

// The voxel oracle's azimuth: principal axis of the inside samples' covariance, in world x/y.
double voxel_azimuth(const Case& c) {
  const auto samples = samples_of(c, kShape, 0);
  const auto components = geotandem::testing::voxel_components(samples, kShape, 0.0f);
  EXPECT_EQ(components.size(), 1u) << c.name;
  const auto cov = components.at(0).covariance(); // ii, ij, ik, jj, jk, kk
  const auto& f = fixtures::test_geometry(kShape).affine;
  // World (x, y) = A (i, j): covariance A C A^T.
  const double a = f.xi, b = f.xj, d = f.yi, e = f.yj;
  const double cii = cov[0], cij = cov[1], cjj = cov[3];
  const double cxx = a * a * cii + 2 * a * b * cij + b * b * cjj;
  const double cyy = d * d * cii + 2 * d * e * cij + e * e * cjj;
  const double cxy = a * d * cii + (a * e + b * d) * cij + b * e * cjj;
  const double theta = 0.5 * std::atan2(2.0 * cxy, cxx - cyy) * 180.0 / std::numbers::pi;
  double az = std::fmod(90.0 - theta, 180.0);
  return az < 0 ? az + 180.0 : az;
}

void expect_closed(const mesh::SurfaceMesh& s, const std::string& what) {
  const mesh::TopologyReport r = mesh::check_topology(s);
  EXPECT_TRUE(r.is_closed_manifold()) << what << ": " << r.summary();
  EXPECT_EQ(r.degenerate_triangles, 0u) << what << ": " << r.summary();
  EXPECT_EQ(r.unreferenced_vertices, 0u) << what << ": " << r.summary();
}

TEST(Caps, MarchingCubesClosesEveryCutBodyWithThePaddedVolume) {
  for (const Case& c : cases()) {
    const auto v = cube_of(c);
    const double oracle = mesh::enclosed_volume(padded_surface(c));
    ASSERT_GT(oracle, 100.0) << c.name;
    for (int axis = 0; axis < 3; ++axis) {
      const std::string what = c.name + ", axis " + std::to_string(axis);
      McOptions options;
      options.axis = axis;
      const mesh::SurfaceMesh s = extract_surface(*v, cube_cells(kShape), options);
      expect_closed(s, what);
      EXPECT_NEAR(mesh::enclosed_volume(s), oracle, 0.01 * oracle) << what;
      const mesh::ComponentStats stats = mesh::measure_component(s, v->geometry());
      EXPECT_TRUE(stats.closed) << what;
      EXPECT_EQ(stats.cut_faces, c.faces) << what << ": " << mesh::cut_faces_text(stats.cut_faces);
      EXPECT_GT(stats.cap_area, 0.0) << what;
      EXPECT_LT(stats.cap_area, 0.6 * stats.area) << what;

      // Without caps: the open surface the isovalue makes, exactly.
      options.caps = false;
      const mesh::SurfaceMesh open = extract_surface(*v, cube_cells(kShape), options);
      const mesh::SurfaceMesh uncapped = mesh::without_caps(s, kShape);
      EXPECT_EQ(uncapped.triangles.size(), open.triangles.size()) << what;
      EXPECT_EQ(uncapped.points.size(), open.points.size()) << what;
      EXPECT_GT(mesh::check_topology(uncapped).boundary_edges, 0u) << what;
      const mesh::ComponentStats open_stats = mesh::measure_component(open, v->geometry());
      EXPECT_FALSE(open_stats.closed) << what;
      EXPECT_EQ(open_stats.cut_faces, c.faces) << what;
      EXPECT_EQ(open_stats.cap_area, 0.0) << what;
    }
  }
}

TEST(Caps, CapsAreFoundAgainInWorldCoordinates) {
  const Case c = cases()[6];
  const auto v = cube_of(c);
  const mesh::SurfaceMesh s = extract_surface(*v, cube_cells(kShape), McOptions{});
  const mesh::SurfaceMesh world = mesh::to_world(s, v->geometry());
  const mesh::SurfaceMesh a = mesh::without_world_caps(world, v->geometry());
  const mesh::SurfaceMesh b = mesh::without_caps(s, kShape);
  EXPECT_EQ(a.triangles.size(), b.triangles.size());
  EXPECT_LT(a.triangles.size(), s.triangles.size());
  EXPECT_EQ(mesh::parse_cut_faces("i-,k+"), 0x21);
  EXPECT_EQ(mesh::cut_faces_text(0x21), "i-,k+");
  EXPECT_EQ(mesh::parse_cut_faces(""), 0);
  EXPECT_THROW(mesh::parse_cut_faces("i-,x+"), InvalidArgument);
}

TEST(Caps, TandemInOneAndManyBlocksMeasuresCutBodiesAsClosedSolids) {
  for (const Case& c : cases()) {
    const auto v = cube_of(c);
    const double oracle = mesh::measure_component(padded_surface(c), v->geometry()).volume;
    const double azimuth = voxel_azimuth(c);
    std::vector<fixtures::CollectingSink> sinks(4);
    const std::int64_t sizes[4] = {0, 8, 0, 16};
    for (int run = 0; run < 4; ++run) {
      const int axis = run < 2 ? 0 : 2;
      const std::string what = c.name + ", block size " + std::to_string(sizes[run]) + ", axis " + std::to_string(axis);
      TandemOptions options;
      options.axis = axis;
      const BlocksStats stats = extract_blocks(*v, cube_cells(kShape), sizes[run], options, &sinks[run]);
      if (sizes[run] > 0) {
        EXPECT_GT(stats.leaves, 8u) << what;
      }
      EXPECT_EQ(stats.tandem.remaining_triangles, 0u) << what;
      ASSERT_EQ(sinks[run].components.size(), 1u) << what;
      const mesh::Component& body = sinks[run].components[0];
      expect_closed(body.surface, what);
      EXPECT_TRUE(body.stats.closed) << what;
      EXPECT_EQ(body.stats.cut_faces, c.faces) << what << ": " << mesh::cut_faces_text(body.stats.cut_faces);
      EXPECT_GT(body.stats.cap_area, 0.0) << what;
      EXPECT_NEAR(body.stats.volume, oracle, 0.01 * oracle) << what;
      EXPECT_LE(mesh::axial_difference_deg(body.stats.azimuth, azimuth), 2.0)
          << what << ": measured " << body.stats.azimuth << ", voxels " << azimuth;
      // The simplification works on the caps too.
      EXPECT_LT(body.surface.triangles.size(),
                extract_surface(*v, cube_cells(kShape), McOptions{}).triangles.size() / 2)
          << what;
    }
    for (int run = 1; run < 4; ++run) {
      EXPECT_EQ(sinks[run].components[0].key, sinks[0].components[0].key) << c.name << ", run " << run;
      EXPECT_NEAR(sinks[run].components[0].stats.volume, sinks[0].components[0].stats.volume, 0.01 * oracle)
          << c.name << ", run " << run;
    }
  }
}

// A ball whose only sample on an outer face holds exactly the isovalue: inside (value >= iso), so
// marching cubes makes a cap a 1/256 voxel wide around it. Simplification may remove every cap
// triangle in one block layout and keep some in another, but the vertex on the face stays there
// (its coordinate on the face is fixed): the body is cut by that face in every layout, as at full
// resolution.
TEST(Caps, ABodyTouchingAFaceAtOneSampleIsCutThereInEveryLayout) {
  struct Touch {
    std::string name;
    std::array<double, 3> centre;
    std::uint8_t face;
  };
  const double hi[3] = {static_cast<double>(kShape[0] - 1), static_cast<double>(kShape[1] - 1),
                        static_cast<double>(kShape[2] - 1)};
  constexpr double kRadius = 12.0;
  const std::vector<Touch> touches = {{"i+", {hi[0] - kRadius, 36.0, 28.0}, 0x02},
                                      {"j-", {40.0, kRadius, 27.0}, 0x04},
                                      {"k+", {39.0, 35.0, hi[2] - kRadius}, 0x20}};
  for (const Touch& t : touches) {
    const auto cube = blocks_test::sample(fixtures::sphere(t.centre, kRadius), kShape); // 0 exactly at the touch
    const volume::Volume& v = *cube;
    const mesh::ComponentStats full =
        mesh::measure_component(extract_surface(v, cube_cells(kShape), McOptions{}), v.geometry());
    ASSERT_EQ(full.cut_faces, t.face) << t.name << ": " << mesh::cut_faces_text(full.cut_faces);
    const std::int64_t sizes[3] = {0, 8, 16};
    for (int axis : {0, 1, 2})
      for (std::int64_t size : sizes) {
        const std::string what = t.name + ", block size " + std::to_string(size) + ", axis " + std::to_string(axis);
        TandemOptions options;
        options.axis = axis;
        fixtures::CollectingSink sink;
        extract_blocks(v, cube_cells(kShape), size, options, &sink);
        ASSERT_EQ(sink.components.size(), 1u) << what;
        const mesh::Component& body = sink.components[0];
        expect_closed(body.surface, what);
        EXPECT_EQ(body.stats.cut_faces, t.face) << what << ": " << mesh::cut_faces_text(body.stats.cut_faces);
        EXPECT_NEAR(body.stats.volume, full.volume, 0.01 * full.volume) << what;
      }
  }
}

} // namespace
} // namespace geotandem::tandem
