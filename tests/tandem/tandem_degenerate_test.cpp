// Single-block extraction (marching cubes + tandem simplification) on degenerate inputs: constant
// cubes, a single voxel above iso (inside and on a corner), everything above iso but a hole, NaN
// samples and the NaN policy of files.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/component.hpp"
#include "geotandem/mesh/measure.hpp"
#include "geotandem/mesh/quality.hpp"
#include "geotandem/mesh/topology.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "geotandem/tandem/tandem.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/volume/volume.hpp"
#include "scratch.hpp"
#include "simplify_fixtures.hpp"

namespace geotandem::tandem {
namespace {

using Collect = fixtures::CollectingSink;
using Index3 = volume::Index3;

// The E0 guarantee of docs/algorithm.md at the default E0 (0.5 voxel): max <= E0.
constexpr double kMaxDistance = 0.5;

std::size_t offset(const Index3& shape, std::int64_t i, std::int64_t j, std::int64_t k) {
  return static_cast<std::size_t>((i * shape[1] + j) * shape[2] + k);
}

volume::Geometry small_geometry(const Index3& shape) {
  volume::Geometry g;
  g.shape = shape;
  return g;
}

std::vector<mesh::Component> run(const volume::Volume& volume, float iso = 0.5f, int axis = 0, bool caps = true) {
  Collect sink;
  TandemOptions options;
  options.iso = iso;
  options.axis = axis;
  options.caps = caps;
  extract_block(volume, cube_cells(volume.geometry().shape), options, &sink);
  return sink.components;
}

TEST(AnalyticDegenerate, ConstantCubesHaveNoSurfaceOrAreOneCappedBody) {
  const Index3 shape{9, 10, 11};
  for (float value : {0.0f, 0.5f, 1.0f}) { // below, exactly at and above the iso value
    SCOPED_TRACE("value " + std::to_string(value));
    const volume::MemoryVolume v(small_geometry(shape), std::vector<float>(990, value));
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_TRUE(run(v, 0.5f, axis, false).empty()); // without caps no isosurface at all
      const auto components = run(v, 0.5f, axis);
      if (value < 0.5f) {
        EXPECT_TRUE(components.empty());
        continue;
      }
      // Inside everywhere: the caps make the cube itself one closed body, cut by every face.
      ASSERT_EQ(components.size(), 1u);
      EXPECT_TRUE(mesh::check_topology(components[0].surface).is_closed_manifold());
      EXPECT_NEAR(mesh::enclosed_volume(components[0].surface), 8.0 * 9.0 * 10.0, 1e-9);
      EXPECT_EQ(components[0].stats.cut_faces, 0x3f);
      EXPECT_LE(components[0].surface.triangle_count(), 12u * 4u); // flat faces simplify to little
    }
  }
}

TEST(AnalyticDegenerate, SingleVoxelAboveIsoIsOneSmallClosedBody) {
  const Index3 shape{7, 8, 9};
  std::vector<float> values(7 * 8 * 9, 0.0f);
  values[offset(shape, 3, 4, 4)] = 1.0f;
  const volume::MemoryVolume v(small_geometry(shape), values);
  for (int axis = 0; axis < 3; ++axis) {
    const auto components = run(v, 0.5f, axis);
    ASSERT_EQ(components.size(), 1u);
    const mesh::SurfaceMesh& s = components[0].surface;
    const mesh::TopologyReport topo = mesh::check_topology(s);
    EXPECT_TRUE(topo.is_closed_manifold()) << topo.summary();
    EXPECT_EQ(topo.euler_characteristic, 2);
    // The octahedron with vertices half a voxel from the sample: 4/3 * 0.5^3. Simplification may
    // only keep or shrink it (it cannot vanish: at least a tetrahedron remains).
    // Collapses keep the enclosed volume (SimplifyOptions::preserve_volume), so the vertices that
    // remain move outwards, up to about a voxel from the sample.
    EXPECT_GE(s.triangle_count(), 4u);
    EXPECT_NEAR(mesh::enclosed_volume(s), 4.0 / 3.0 * 0.125, 0.01 * 4.0 / 3.0 * 0.125);
    const mesh::SurfaceMesh octahedron = extract_surface(v, cube_cells(shape), McOptions{0.5f, axis});
    EXPECT_EQ(octahedron.triangle_count(), 8u);
    EXPECT_LE(mesh::hausdorff_distance(s, octahedron).max, kMaxDistance);
  }
  // The same voxel on a corner of the cube: one piece cut by the border, closed by three caps
  // (the corner of the octahedron: 1/8 of it); without caps, open.
  values.assign(values.size(), 0.0f);
  values[offset(shape, 0, 0, 0)] = 1.0f;
  const volume::MemoryVolume corner(small_geometry(shape), values);
  const auto components = run(corner);
  ASSERT_EQ(components.size(), 1u);
  EXPECT_TRUE(components[0].stats.cut_by_border);
  EXPECT_EQ(components[0].stats.cut_faces, 0x15); // i-, j-, k-
  EXPECT_TRUE(components[0].stats.closed);
  EXPECT_TRUE(mesh::check_topology(components[0].surface).is_closed_manifold());
  EXPECT_NEAR(mesh::enclosed_volume(components[0].surface), 4.0 / 3.0 * 0.125 / 8.0, 0.02 * 4.0 / 3.0 * 0.125 / 8.0);
  const auto open = run(corner, 0.5f, 0, false);
  ASSERT_EQ(open.size(), 1u);
  EXPECT_TRUE(open[0].stats.cut_by_border);
  EXPECT_FALSE(open[0].stats.closed);
  EXPECT_TRUE(mesh::check_topology(open[0].surface).is_manifold());
}

TEST(AnalyticDegenerate, AllSamplesAboveIsoExceptAHoleGivesOnlyTheHole) {
  // Everything inside: without caps the cube's faces are not a surface (with caps they are one
  // body, the cube). One outside sample in the middle is a cavity: one closed surface of negative
  // enclosed volume.
  const Index3 shape{8, 8, 8};
  std::vector<float> values(512, 2.0f);
  const volume::MemoryVolume full(small_geometry(shape), values);
  EXPECT_TRUE(run(full, 0.5f, 0, false).empty());
  values[offset(shape, 4, 3, 4)] = 0.0f;
  const volume::MemoryVolume holed(small_geometry(shape), values);
  auto components = run(holed, 0.5f, 2, false);
  ASSERT_EQ(components.size(), 1u);
  EXPECT_TRUE(mesh::check_topology(components[0].surface).is_closed_manifold());
  EXPECT_LT(mesh::enclosed_volume(components[0].surface), 0.0);
  // With caps: the cube (positive volume) and the cavity, two closed surfaces.
  components = run(holed, 0.5f, 2);
  ASSERT_EQ(components.size(), 2u);
  double total = 0.0;
  for (const auto& c : components) {
    EXPECT_TRUE(mesh::check_topology(c.surface).is_closed_manifold());
    total += mesh::enclosed_volume(c.surface);
  }
  EXPECT_GT(total, 7.0 * 7.0 * 7.0 - 1.0);
  EXPECT_LT(total, 7.0 * 7.0 * 7.0);
}

// NaN policy (docs/marching-cubes.md): marching cubes treats a NaN sample as outside. Files go
// through open_volume's NanPolicy first: `error` (default) refuses the first NaN with a DataError,
// `fill` replaces it by the fill value (lowest float: outside).
std::vector<float> ball(const Index3& shape, std::array<double, 3> centre, double radius) {
  std::vector<float> values(static_cast<std::size_t>(shape[0] * shape[1] * shape[2]));
  for (std::int64_t i = 0; i < shape[0]; ++i)
    for (std::int64_t j = 0; j < shape[1]; ++j)
      for (std::int64_t k = 0; k < shape[2]; ++k) {
        const double r = std::hypot(static_cast<double>(i) - centre[0], static_cast<double>(j) - centre[1],
                                    static_cast<double>(k) - centre[2]);
        values[offset(shape, i, j, k)] = static_cast<float>(std::clamp(0.5 + 0.25 * (radius - r), 0.0, 1.0));
      }
  return values;
}

TEST(AnalyticDegenerate, NanSamplesAreOutside) {
  const Index3 shape{20, 20, 20};
  std::vector<float> values = ball(shape, {9.6, 10.2, 9.8}, 6.0);
  const volume::MemoryVolume clean(small_geometry(shape), values);
  const auto reference = run(clean);
  ASSERT_EQ(reference.size(), 1u);
  const double v_ref = mesh::enclosed_volume(reference[0].surface);

  // NaN far from the body (in the outside region) changes nothing.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> far = values;
  far[offset(shape, 1, 1, 1)] = nan;
  far[offset(shape, 18, 2, 17)] = nan;
  far[offset(shape, 0, 19, 0)] = nan;
  const auto same = run(volume::MemoryVolume(small_geometry(shape), far));
  ASSERT_EQ(same.size(), 1u);
  EXPECT_EQ(same[0].key, reference[0].key);
  EXPECT_EQ(same[0].surface.points, reference[0].surface.points);

  // A NaN deep inside is a one-sample cavity: a second, inner closed surface.
  std::vector<float> holed = values;
  holed[offset(shape, 10, 10, 10)] = nan;
  const auto two = run(volume::MemoryVolume(small_geometry(shape), holed));
  ASSERT_EQ(two.size(), 2u);
  double v = 0.0;
  for (const mesh::Component& c : two) {
    EXPECT_TRUE(mesh::check_topology(c.surface).is_closed_manifold()) << c.key;
    for (const mesh::Point& p : c.surface.points)
      for (double x : p)
        EXPECT_TRUE(std::isfinite(x));
    v += mesh::enclosed_volume(c.surface);
  }
  EXPECT_LT(v, v_ref);
  EXPECT_GT(v, v_ref - 1.5);

  // The iso value itself must not be NaN.
  EXPECT_THROW(run(clean, nan), InvalidArgument);
}

TEST(AnalyticDegenerate, NanPolicyOfFilesReachesTheExtraction) {
  const Index3 shape{16, 16, 16};
  std::vector<float> values = ball(shape, {7.7, 8.1, 8.3}, 4.5);
  values[offset(shape, 2, 13, 3)] = std::numeric_limits<float>::quiet_NaN();
  testing::ScratchDir dir;
  const std::string path = dir.file("nan.raw");
  volume::write_volume(volume::MemoryVolume(small_geometry(shape), values), path);

  const auto strict = volume::open_volume(path);
  EXPECT_THROW(run(*strict), DataError);

  volume::OpenOptions fill;
  fill.nan_policy = volume::NanPolicy::fill;
  const auto filled = volume::open_volume(path, fill);
  const auto components = run(*filled);
  ASSERT_EQ(components.size(), 1u);
  EXPECT_TRUE(mesh::check_topology(components[0].surface).is_closed_manifold());
  EXPECT_GT(mesh::enclosed_volume(components[0].surface), 0.0);
}

} // namespace
} // namespace geotandem::tandem
