// The tandem on smooth bodies inside the cube: closed 2-manifolds, close to the full-resolution
// surface, same enclosed volume, far fewer triangles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "geotandem/mesh/measure.hpp"
#include "geotandem/mesh/quality.hpp"
#include "geotandem/mesh/topology.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "simplify_fixtures.hpp"

namespace geotandem::tandem {
namespace {

using fixtures::CollectingSink;

// The E0 guarantee (docs/algorithm.md): the largest distance between the simplified and the
// full-resolution surfaces is at most E0 (no slack); RMS distances about 0.6 E0 at most.
constexpr double kDistanceSlack = 0.0; // times E0: max distance <= E0
constexpr double kRmsFactor = 0.6;     // rms distance <= 0.6 E0

struct BodyRun {
  CollectingSink sink;
  TandemStats stats;
  mesh::SurfaceMesh full;
  std::vector<std::uint64_t> full_ids;
};

void run_body(BodyRun& run, const fixtures::Input& input, int axis, SimplifyOptions simplify = {}) {
  const volume::Box cells = input.cells();
  run.full = input.full(cells, axis, &run.full_ids);
  const auto source = input.layers(cells, axis);
  WorkingSurface surface(fixtures::test_geometry(input.shape()), Region::block(cells, cells), axis, simplify,
                         &run.sink);
  run.sink.surface = &surface;
  TandemOptions options;
  options.axis = axis;
  options.simplify = simplify;
  run.stats = run_tandem(*source, surface, options);
  EXPECT_EQ(surface.triangle_count(), 0u) << "everything inside the cube is dumped at the end";
  EXPECT_EQ(surface.vertex_count(), 0u);
}

void expect_faithful(const mesh::SurfaceMesh& simplified, const mesh::SurfaceMesh& full, double e0, double max_ratio) {
  const mesh::TopologyReport topo = mesh::check_topology(simplified);
  const mesh::TopologyReport full_topo = mesh::check_topology(full);
  ASSERT_TRUE(full_topo.is_closed_manifold()) << full_topo.summary();
  EXPECT_TRUE(topo.is_closed_manifold()) << topo.summary();
  EXPECT_EQ(topo.degenerate_triangles, 0u) << topo.summary();
  EXPECT_EQ(topo.euler_characteristic, full_topo.euler_characteristic);
  EXPECT_EQ(topo.components, full_topo.components);
  const double v = mesh::enclosed_volume(simplified), v_full = mesh::enclosed_volume(full);
  EXPECT_NEAR(v / v_full, 1.0, 0.01) << "volume " << v << " vs full resolution " << v_full;
  const mesh::DistanceStats d = mesh::hausdorff_distance(simplified, full, 8);
  EXPECT_LE(d.max, (1.0 + kDistanceSlack) * e0); // the E0 guarantee
  EXPECT_LE(d.rms, kRmsFactor * e0);
  EXPECT_LT(static_cast<double>(simplified.triangle_count()), max_ratio * static_cast<double>(full.triangle_count()))
      << simplified.triangle_count() << " of " << full.triangle_count();
}

TEST(TandemSurface, SphereIsClosedAccurateAndReduced) {
  using fixtures::Mesher;
  for (auto [mesher, axis] : {std::pair{Mesher::marching_cubes, 2}, std::pair{Mesher::tetrahedra, 0}}) {
    SCOPED_TRACE(std::string(fixtures::to_string(mesher)) + ", axis " + std::to_string(axis));
    BodyRun run;
    const volume::Index3 shape{30, 31, 29};
    run_body(run, fixtures::Input(fixtures::sphere({14.3, 15.6, 13.2}, 10.0), shape, mesher), axis);
    ASSERT_EQ(run.sink.components.size(), 1u);
    const mesh::Component& c = run.sink.components[0];
    expect_faithful(c.surface, run.full, 0.5, 0.3);
    // The key is the smallest lattice-edge id of the body.
    EXPECT_EQ(c.key, *std::min_element(run.full_ids.begin(), run.full_ids.end()));
    // Stats come from the measures of the mesh part, in world units (25 m x 25 m x 4 ms bins).
    EXPECT_TRUE(c.stats.closed);
    EXPECT_FALSE(c.stats.cut_by_border);
    EXPECT_EQ(c.stats.triangle_count, c.surface.triangle_count());
    EXPECT_NEAR(c.stats.volume, mesh::enclosed_volume(c.surface) * 25.0 * 25.0 * 4.0, 1e-6 * c.stats.volume);
    // One record per layer, with the triangles held after it.
    ASSERT_EQ(run.stats.layers.size(), static_cast<std::size_t>(shape[axis] - 1));
    std::uint64_t input = 0;
    for (const LayerStats& s : run.stats.layers)
      input += s.input_triangles;
    EXPECT_EQ(input, run.full.triangle_count());
    EXPECT_EQ(run.stats.counters.input_triangles, input);
    EXPECT_GT(run.stats.peak_triangles, 0u);
    EXPECT_LT(run.stats.peak_triangles, input);
  }
}

TEST(TandemSurface, EllipsoidAndTorusKeepTheirTopology) {
  {
    BodyRun run;
    run_body(run, fixtures::Input(fixtures::ellipsoid({20.2, 13.7, 14.9}, {15.0, 8.0, 10.5}), {42, 28, 31}), 1);
    ASSERT_EQ(run.sink.components.size(), 1u);
    expect_faithful(run.sink.components[0].surface, run.full, 0.5, 0.3);
  }
  {
    BodyRun run;
    run_body(run, fixtures::Input(fixtures::torus({19.5, 19.2, 9.7}, 11.0, 4.5), {40, 40, 20}), 2);
    ASSERT_EQ(run.sink.components.size(), 1u);
    const mesh::TopologyReport topo = mesh::check_topology(run.sink.components[0].surface);
    EXPECT_EQ(topo.euler_characteristic, 0) << topo.summary(); // genus one
    expect_faithful(run.sink.components[0].surface, run.full, 0.5, 0.35);
  }
}

TEST(TandemSurface, ExtremeIsotropyValuesStillGiveValidSurfaces) {
  for (double alpha : {0.0, 1.0}) {
    SCOPED_TRACE("alpha " + std::to_string(alpha));
    BodyRun run;
    SimplifyOptions options;
    options.isotropy = alpha;
    run_body(run, fixtures::Input(fixtures::sphere({14.6, 15.3, 14.1}, 10.0), {30, 31, 29}), 0, options);
    ASSERT_EQ(run.sink.components.size(), 1u);
    const mesh::SurfaceMesh& s = run.sink.components[0].surface;
    const mesh::TopologyReport topo = mesh::check_topology(s);
    EXPECT_TRUE(topo.is_closed_manifold()) << topo.summary();
    EXPECT_EQ(topo.euler_characteristic, 2);
    EXPECT_LE(mesh::hausdorff_distance(s, run.full).max, 0.5 + kDistanceSlack * 0.5);
    EXPECT_NEAR(mesh::enclosed_volume(s) / mesh::enclosed_volume(run.full), 1.0, 0.01);
    EXPECT_LT(s.triangle_count(), run.full.triangle_count());
  }
}

TEST(TandemSurface, IsotropyImprovesTriangleShape) {
  // The isotropy term exists to avoid long skinny triangles (the seed's figure 12: anisotropy
  // falls as alpha grows towards 0.9). Measured on a body large enough for the mean over
  // triangles to be stable; the effect at 0.4 is small, at 0.7 clear. The seed's algorithm (no E0
  // guarantee): under the guarantee the isotropic positions are refused more often and alpha has
  // little room at E0 = 0.2 (measured: 0.347 at alpha 0, 0.360 at 0.7).
  double aniso[3];
  int i = 0;
  for (double alpha : {0.0, 0.4, 0.7}) {
    BodyRun run;
    SimplifyOptions options;
    options.isotropy = alpha;
    options.guarantee_distance = false;
    options.max_error = 0.2;
    run_body(run, fixtures::Input(fixtures::ellipsoid({22.1, 17.4, 14.8}, {19.0, 14.0, 11.0}), {45, 36, 31}), 0,
             options);
    ASSERT_EQ(run.sink.components.size(), 1u);
    aniso[i++] = mesh::anisotropy(run.sink.components[0].surface);
  }
  EXPECT_LE(aniso[1], aniso[0] + 0.005);
  EXPECT_LT(aniso[2], aniso[0] - 0.02);
}

} // namespace
} // namespace geotandem::tandem
