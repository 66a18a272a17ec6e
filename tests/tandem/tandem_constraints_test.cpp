// The time lag and the extended time lag, checked on every collapse through an observer, and the
// effect of the extended time lag on the triangles near a block's open faces.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <utility>

#include "geotandem/mesh/quality.hpp"
#include "geotandem/mesh/topology.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "simplify_fixtures.hpp"

namespace geotandem::tandem {
namespace {

using fixtures::CollectingSink;
using fixtures::RecordingObserver;

// A ball crossing the plane i = 20 of a cube of 40 x 30 x 30 samples; the block is the cells with
// i < 20, so the plane is an open face (a neighbour block would extract the rest of the ball).
const volume::Index3 kShape{40, 30, 30};
const volume::Box kBlock{{0, 0, 0}, {20, 29, 29}};
fixtures::Input ball(fixtures::Mesher mesher = fixtures::Mesher::marching_cubes) {
  return fixtures::Input(fixtures::sphere({19.3, 14.6, 14.2}, 9.0), kShape, mesher);
}

struct BlockRun {
  CollectingSink sink;
  RecordingObserver observer;
  std::unique_ptr<WorkingSurface> surface;
  TandemStats stats;
};

void run_block(BlockRun& run, const fixtures::Input& input, const volume::Box& block, int axis,
               SimplifyOptions options) {
  const volume::Box cube = cube_cells(kShape);
  const auto source = input.layers(block, axis);
  run.surface = std::make_unique<WorkingSurface>(fixtures::test_geometry(kShape), Region::block(cube, block), axis,
                                                 options, &run.sink, &run.observer);
  TandemOptions t;
  t.axis = axis;
  t.simplify = options;
  run.stats = run_tandem(*source, *run.surface, t);
}

// Every point of `full` lying on the plane x[axis] = plane is a vertex of `kept` (bit-identical).
void expect_face_vertices_kept(const mesh::SurfaceMesh& full, const mesh::SurfaceMesh& kept, int axis, double plane) {
  std::set<std::array<double, 3>> present(kept.points.begin(), kept.points.end());
  std::size_t on_face = 0;
  for (const auto& p : full.points) {
    if (p[static_cast<std::size_t>(axis)] != plane) continue;
    ++on_face;
    EXPECT_TRUE(present.count(p)) << "vertex (" << p[0] << ", " << p[1] << ", " << p[2]
                                  << ") on the open face was lost";
  }
  EXPECT_GT(on_face, 20u);
}

TEST(TandemConstraints, NoCollapseReachesTheFrontOrAnOpenFace) {
  using fixtures::Mesher;
  for (auto [mesher, axis] : {std::pair{Mesher::marching_cubes, 0}, std::pair{Mesher::tetrahedra, 2}}) {
    SCOPED_TRACE(std::string(fixtures::to_string(mesher)) + ", axis " + std::to_string(axis));
    const fixtures::Input input = ball(mesher);
    BlockRun run;
    run_block(run, input, kBlock, axis, {});
    ASSERT_GT(run.observer.events.size(), 100u);
    std::size_t during_sweep = 0;
    for (const CollapseEvent& e : run.observer.events) {
      ASSERT_LT(e.reach, e.front);
      ASSERT_GT(e.open_face_distance, e.rad);
      ASSERT_LE(e.shape_error, 0.5);
      if (std::isfinite(e.front)) ++during_sweep;
    }
    EXPECT_GT(during_sweep, run.observer.events.size() / 2) << "the tandem simplifies while it extracts";
    // The ball touches the open face: it is not finished, it waits in memory for the neighbour.
    EXPECT_TRUE(run.sink.components.empty());
    EXPECT_GT(run.surface->triangle_count(), 0u);
    EXPECT_GT(run.surface->waiting_edge_count(), 0u);
    const mesh::SurfaceMesh full = input.full(kBlock, axis);
    const mesh::SurfaceMesh kept = run.surface->snapshot();
    expect_face_vertices_kept(full, kept, 0, 20.0);
    const mesh::TopologyReport t = mesh::check_topology(kept);
    EXPECT_TRUE(t.is_manifold()) << t.summary();
    EXPECT_EQ(t.misoriented_edges, 0u);
    EXPECT_LT(kept.triangle_count(), full.triangle_count() / 2);
  }
}

TEST(TandemConstraints, FrontFaceOfABlockIsOpenToo) {
  // The block ends at k = 15 inside the cube: its last cross-section is an open face, which the
  // extended time lag protects after the sweep (activate(inf) lifts only the time lag).
  const volume::Box block{{0, 0, 0}, {39, 29, 15}};
  BlockRun run;
  const fixtures::Input input = ball();
  run_block(run, input, block, 2, {});
  for (const CollapseEvent& e : run.observer.events)
    ASSERT_GT(e.open_face_distance, e.rad);
  const mesh::SurfaceMesh full = input.full(block, 2);
  expect_face_vertices_kept(full, run.surface->snapshot(), 2, 15.0);
}

TEST(TandemConstraints, WithoutTimeLagOnlyTheFrontCrossSectionWaits) {
  SimplifyOptions options;
  options.time_lag = false;
  BlockRun run;
  const volume::Box cube = cube_cells(kShape);
  run_block(run, fixtures::Input(fixtures::sphere({20.2, 14.6, 14.2}, 9.0), kShape), cube, 2, options);
  for (const CollapseEvent& e : run.observer.events)
    ASSERT_LT(std::max(e.a[2], e.b[2]), e.front);
  ASSERT_EQ(run.sink.components.size(), 1u);
  EXPECT_TRUE(mesh::check_topology(run.sink.components[0].surface).is_closed_manifold());
}

TEST(TandemConstraints, WithoutExtendedTimeLagOnlyFaceVerticesAreFrozen) {
  SimplifyOptions options;
  options.extended_time_lag = false;
  BlockRun run;
  const fixtures::Input input = ball();
  run_block(run, input, kBlock, 2, options);
  const Region region = run.surface->region();
  std::size_t near_face = 0;
  for (const CollapseEvent& e : run.observer.events) {
    ASSERT_FALSE(region.on_open_face(e.a));
    ASSERT_FALSE(region.on_open_face(e.b));
    if (e.open_face_distance <= e.rad) ++near_face;
  }
  EXPECT_GT(near_face, 0u) << "without the extended time lag, collapses come close to the face";
  expect_face_vertices_kept(input.full(kBlock, 2), run.surface->snapshot(), 0, 20.0);
}

// Anisotropy of the triangles having a vertex within `band` of the plane i = 20.
double anisotropy_near_face(const mesh::SurfaceMesh& s, double band) {
  mesh::SurfaceMesh near;
  near.points = s.points;
  for (const auto& t : s.triangles) {
    bool close = false;
    for (std::uint32_t v : t)
      close = close || std::abs(s.points[v][0] - 20.0) <= band;
    if (close) near.triangles.push_back(t);
  }
  return mesh::anisotropy(near);
}

TEST(TandemConstraints, ExtendedTimeLagGivesBetterTrianglesAtBlockFaces) {
  // The seed's figure 9: freezing only the face vertices lets long, thin triangles reach the face.
  // The seed's algorithm (no E0 guarantee): the guarantee keeps short triangles near the face
  // either way, which hides the effect (measured: 0.60 with the lag against 0.54 frozen).
  double with_lag = 0.0, frozen = 0.0;
  const fixtures::Input input = ball();
  for (bool extended : {true, false}) {
    SimplifyOptions options;
    options.extended_time_lag = extended;
    options.guarantee_distance = false;
    BlockRun run;
    run_block(run, input, kBlock, 2, options);
    const double a = anisotropy_near_face(run.surface->snapshot(), 3.0);
    (extended ? with_lag : frozen) = a;
  }
  EXPECT_LT(with_lag + 0.05, frozen) << "near-face anisotropy: extended time lag " << with_lag << ", frozen " << frozen;
}

} // namespace
} // namespace geotandem::tandem
