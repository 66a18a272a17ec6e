// Blocks and merging (the seed's section 3.2): the same cube split into 1, 2, 8 and 64 blocks gives
// the same components; merges of L-shaped regions work; the extended time lag is what keeps the
// seams good; and merges of surfaces that do not fit together are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <vector>

#include "blocks_support.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/tandem/block_tree.hpp"
#include "geotandem/tandem/blocks.hpp"
#include "geotandem/tandem/serialize.hpp"

namespace geotandem::tandem {
namespace {

using blocks_test::kShape;
using fixtures::CollectingSink;

struct BlocksRun {
  CollectingSink sink;
  BlocksStats stats;
};

SimplifyOptions fine() {
  SimplifyOptions s;
  s.max_error = blocks_test::kMaxError;
  return s;
}

void run_blocks(BlocksRun& run, const volume::Volume& volume, std::int64_t block_size,
                SimplifyOptions simplify = fine(), CollapseObserver* observer = nullptr, int axis = 0) {
  TandemOptions options;
  options.axis = axis;
  options.simplify = simplify;
  options.observer = observer;
  std::unique_ptr<WorkingSurface> remaining;
  run.stats = extract_blocks(volume, cube_cells(kShape), block_size, options, &run.sink, &remaining);
  ASSERT_TRUE(remaining);
  EXPECT_EQ(remaining->triangle_count(), 0u) << "the root covers the whole cube: nothing may wait";
  EXPECT_EQ(remaining->component_count(), 0u);
}

TEST(TandemBlocks, SameComponentsWhateverTheBlockSize) {
  const auto volume = blocks_test::sample(blocks_test::bodies(), kShape);
  BlocksRun one;
  run_blocks(one, *volume, 0);
  ASSERT_EQ(one.stats.leaves, 1u);
  ASSERT_EQ(one.sink.components.size(), blocks_test::kBodies);
  for (const mesh::Component& c : one.sink.components)
    EXPECT_TRUE(mesh::check_topology(c.surface).is_closed_manifold());

  for (auto [block_size, leaves] : {std::pair{48, 2u}, std::pair{32, 8u}, std::pair{16, 64u}}) {
    SCOPED_TRACE("block size " + std::to_string(block_size));
    BlocksRun run;
    run_blocks(run, *volume, block_size);
    EXPECT_EQ(run.stats.leaves, leaves);
    EXPECT_EQ(run.stats.merges, leaves - 1);
    EXPECT_GT(run.stats.wire_bytes, 0u);
    EXPECT_GT(run.stats.seam_collapses, 0u) << "the seams are simplified after the merges";
    EXPECT_EQ(run.stats.tandem.counters.components_dumped, blocks_test::kBodies);
    EXPECT_EQ(run.stats.tandem.counters.input_triangles, one.stats.tandem.counters.input_triangles)
        << "every marching-cubes triangle is made once, by exactly one block";
    blocks_test::expect_same_components(one.sink.components, run.sink.components);
    // Simplified about as much as one block.
    std::size_t t1 = 0, tn = 0;
    for (const auto& c : one.sink.components)
      t1 += c.surface.triangle_count();
    for (const auto& c : run.sink.components)
      tn += c.surface.triangle_count();
    EXPECT_LT(static_cast<double>(tn), 1.1 * static_cast<double>(t1)) << t1 << " triangles in one block, " << tn;
  }
}

// Share of triangles with a corner within `band` of an inner plane of the 64-block tree, and the
// anisotropy and the share of small angles of those triangles.
struct SeamQuality {
  double anisotropy = 0.0;
  double small_angles = 0.0;
  std::size_t triangles = 0;
};

SeamQuality seam_quality(const std::vector<mesh::Component>& components, double band) {
  static const std::vector<std::pair<int, double>> planes = {{0, 16.0}, {0, 32.0}, {0, 48.0}, {1, 12.0}, {1, 24.0},
                                                             {1, 36.0}, {2, 12.0}, {2, 24.0}, {2, 36.0}};
  mesh::SurfaceMesh near;
  for (const mesh::Component& c : components) {
    const auto base = static_cast<std::uint32_t>(near.points.size());
    near.points.insert(near.points.end(), c.surface.points.begin(), c.surface.points.end());
    for (const auto& t : c.surface.triangles) {
      bool close = false;
      for (std::uint32_t v : t)
        for (const auto& [axis, plane] : planes)
          close = close || std::abs(c.surface.points[v][static_cast<std::size_t>(axis)] - plane) <= band;
      if (close) near.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    }
  }
  return {mesh::anisotropy(near), mesh::small_angle_share(near, 10.0), near.triangle_count()};
}

TEST(TandemBlocks, SameComponentsAlongAnotherAxis) {
  // Extracted along k, the sweep crosses the k-planes of the tree instead of running along them.
  const auto volume = blocks_test::sample(blocks_test::bodies(), kShape);
  BlocksRun one, eight;
  run_blocks(one, *volume, 0, fine(), nullptr, 2);
  run_blocks(eight, *volume, 32, fine(), nullptr, 2);
  ASSERT_EQ(one.sink.components.size(), blocks_test::kBodies);
  EXPECT_EQ(eight.stats.leaves, 8u);
  blocks_test::expect_same_components(one.sink.components, eight.sink.components);
}

TEST(TandemBlocks, ExtendedTimeLagKeepsTheSeamsGood) {
  // The seed's figure 9 and 12: without the extended time lag only the vertices on open faces are
  // frozen, the triangles next to them are stretched towards the face before the neighbour
  // arrives, and the seams stay visibly worse after the merge.
  const auto volume = blocks_test::sample(blocks_test::bodies(), kShape);
  // At the default E0 (0.5 voxel) the bodies are coarse and the seams weigh most.
  BlocksRun one, with_lag, frozen;
  const SimplifyOptions defaults;
  run_blocks(one, *volume, 0, defaults);
  fixtures::RecordingObserver with_lag_events, frozen_events;
  run_blocks(with_lag, *volume, 16, defaults, &with_lag_events);
  SimplifyOptions off;
  off.extended_time_lag = false;
  run_blocks(frozen, *volume, 16, off, &frozen_events);
  // The mechanism, in every leaf and every merge: no collapse's ball reaches an open face with
  // the extended time lag; without it, many do.
  auto reaching = [](const fixtures::RecordingObserver& o) {
    return std::count_if(o.events.begin(), o.events.end(),
                         [](const CollapseEvent& e) { return e.open_face_distance <= e.rad; });
  };
  EXPECT_EQ(reaching(with_lag_events), 0);
  EXPECT_GT(reaching(frozen_events), 100);
  ASSERT_EQ(frozen.sink.components.size(), blocks_test::kBodies);
  for (const mesh::Component& c : frozen.sink.components)
    EXPECT_TRUE(mesh::check_topology(c.surface).is_closed_manifold());

  const SeamQuality q1 = seam_quality(one.sink.components, 1.0);
  const SeamQuality qw = seam_quality(with_lag.sink.components, 1.0);
  const SeamQuality qf = seam_quality(frozen.sink.components, 1.0);
  std::printf("near block planes (64 blocks): one block anisotropy %.4f small angles %.4f (%zu triangles); "
              "extended time lag %.4f %.4f (%zu); frozen face vertices %.4f %.4f (%zu)\n",
              q1.anisotropy, q1.small_angles, q1.triangles, qw.anisotropy, qw.small_angles, qw.triangles, qf.anisotropy,
              qf.small_angles, qf.triangles);
  EXPECT_NEAR(qw.anisotropy, q1.anisotropy, 0.02) << "with the extended time lag the seams look like no seam";
  EXPECT_GT(qf.anisotropy, qw.anisotropy + 0.01) << "freezing only the face vertices degrades the seams";
  EXPECT_GT(qf.small_angles, qw.small_angles) << "more slivers at the seams without the extended time lag";
}

// One block of the 2 x 2 split of the cube across i = 32 and j = 24 (full along k).
std::unique_ptr<WorkingSurface> quarter(const volume::Volume& volume, int qi, int qj, CollectingSink& sink) {
  const volume::Box cube = cube_cells(kShape);
  volume::Box cells = cube;
  cells.lo[0] = qi == 0 ? 0 : 32;
  cells.hi[0] = qi == 0 ? 32 : cube.hi[0];
  cells.lo[1] = qj == 0 ? 0 : 24;
  cells.hi[1] = qj == 0 ? 24 : cube.hi[1];
  TandemOptions options;
  options.axis = 0;
  options.simplify = fine();
  std::unique_ptr<WorkingSurface> surface;
  extract_block(volume, cells, options, &sink, &surface);
  return surface;
}

// The test cube's whole-cube extraction, and its quarters extracted into one sink.
struct Quarters {
  const std::unique_ptr<volume::MemoryVolume> volume = blocks_test::sample(blocks_test::bodies(), kShape);
  BlocksRun one;
  CollectingSink sink;
  Quarters() { run_blocks(one, *volume, 0); }
  std::unique_ptr<WorkingSurface> operator()(int qi, int qj) { return quarter(*volume, qi, qj, sink); }
};

TEST(TandemBlocks, LShapedRegionsMerge) {
  // A node merged with a nephew (restricted adjacency) gives an L-shaped region: its open faces
  // are the parts of the boundary the last quarter will arrive at.
  Quarters q;
  auto a = q(0, 0), b = q(1, 0), c = q(0, 1), d = q(1, 1);
  a->merge(std::move(*b));
  ASSERT_EQ(a->region().blocks().size(), 1u) << "two brothers make one box";
  a->merge(std::move(*c));
  const Region& l_shape = a->region();
  ASSERT_EQ(l_shape.blocks().size(), 2u);
  // The open faces of the L: the two sides of the missing quarter (i = 32 for j > 24, j = 24 for
  // i > 32).
  ASSERT_EQ(l_shape.open_faces().size(), 2u);
  for (const OpenFace& f : l_shape.open_faces())
    EXPECT_TRUE((f.axis == 0 && f.plane == 32.0) || (f.axis == 1 && f.plane == 24.0));
  EXPECT_TRUE(l_shape.on_open_face({32.0, 30.0, 5.0}));
  EXPECT_FALSE(l_shape.on_open_face({32.0, 20.0, 5.0})) << "inside the L, the seam is no face any more";
  EXPECT_GT(a->component_count(), 0u) << "the bodies crossing into the last quarter still wait";
  a->merge(std::move(*d));
  a->finish();
  EXPECT_EQ(a->triangle_count(), 0u);
  blocks_test::expect_same_components(q.one.sink.components, q.sink.components);
}

// The triangles of a snapshot as sorted corner triples: the same surface whatever the numbering.
std::vector<std::array<std::array<double, 3>, 3>> triangle_set(const mesh::SurfaceMesh& m) {
  std::vector<std::array<std::array<double, 3>, 3>> out;
  for (const auto& t : m.triangles) {
    std::array<std::array<double, 3>, 3> corners{m.points[t[0]], m.points[t[1]], m.points[t[2]]};
    std::rotate(corners.begin(), std::min_element(corners.begin(), corners.end()), corners.end());
    out.push_back(corners);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(TandemBlocks, CompactingASurfaceSetAsideChangesNothingButItsStorage) {
  // compact() renumbers everything (the queues, the components, the last layer's ids): the
  // surface, its waiting edges and its components stay, and the merges go on to the components
  // of the whole-cube extraction.
  Quarters q;
  auto a = q(0, 0), b = q(1, 0);
  const auto before = triangle_set(a->snapshot());
  const std::size_t waiting = a->waiting_edge_count(), components = a->component_count();
  ASSERT_GT(waiting, 0u);
  const std::uint64_t collections = a->counters().garbage_collections;
  a->compact();
  EXPECT_EQ(a->counters().garbage_collections, collections + 1) << "collapses and dumps left storage to give back";
  EXPECT_EQ(triangle_set(a->snapshot()), before);
  EXPECT_EQ(a->waiting_edge_count(), waiting);
  EXPECT_EQ(a->component_count(), components);
  a->merge(std::move(*b));
  a->compact();
  const std::uint64_t after_merge = a->counters().garbage_collections;
  a->compact();
  EXPECT_EQ(a->counters().garbage_collections, after_merge) << "nothing left to give back";
  auto c = q(0, 1), d = q(1, 1);
  c->compact();
  c->merge(std::move(*d));
  a->merge(std::move(*c));
  a->finish();
  EXPECT_EQ(a->triangle_count(), 0u);
  blocks_test::expect_same_components(q.one.sink.components, q.sink.components);
}

TEST(TandemBlocks, AMergePlacesEveryParkedEdgeTheNewBlocksFree) {
  // A merge places again only the parked edges whose ball reaches the other side's blocks (the
  // faces it closes lie there). Placing every parked edge again afterwards must then change
  // nothing: no edge left parked may collapse. Checked after merges of brothers, of an L into a
  // surface compacted before (its parked edges listed again) and of the last quarter.
  const auto expect_nothing_more_to_free = [](WorkingSurface& s, const char* what) {
    const auto before = triangle_set(s.snapshot());
    const std::size_t waiting = s.waiting_edge_count(), components = s.component_count();
    const std::uint64_t collapses = s.counters().collapses;
    s.set_region(s.region());
    s.finish();
    EXPECT_EQ(s.counters().collapses, collapses) << what;
    EXPECT_EQ(triangle_set(s.snapshot()), before) << what;
    EXPECT_EQ(s.waiting_edge_count(), waiting) << what;
    EXPECT_EQ(s.component_count(), components) << what;
  };
  Quarters q;
  auto a = q(0, 0), b = q(1, 0), c = q(0, 1), d = q(1, 1);
  const std::uint64_t before_merge = a->counters().collapses + b->counters().collapses;
  a->merge(std::move(*b));
  EXPECT_GT(a->counters().collapses, before_merge) << "the seam's edges were freed and collapsed";
  expect_nothing_more_to_free(*a, "brothers");
  a->compact(); // the larger side takes the other in: its parked edges as listed again here
  a->merge(std::move(*c));
  expect_nothing_more_to_free(*a, "an L after a compaction");
  a->merge(std::move(*d));
  expect_nothing_more_to_free(*a, "the last quarter");
  EXPECT_EQ(a->triangle_count(), 0u);
  blocks_test::expect_same_components(q.one.sink.components, q.sink.components);
}

TEST(TandemBlocks, AMergeLeavesTheParkedEdgesFarFromItsBlocksAlone) {
  // Two brothers make a box whose one open face (j = 24) the third quarter then half closes. The
  // parked edges over the other half still reach an open part of that face: the merge must keep
  // them parked without placing them again. Placing every parked edge again parks each edge still
  // parked after the merge once more (blocked_by_faces counts every parking); so must skipping
  // none. The skipped ones are most of those over the half left open.
  Quarters q;
  auto a = q(0, 0), b = q(1, 0), c = q(0, 1);
  a->merge(std::move(*b));
  ASSERT_GT(a->waiting_edge_count(), 100u);
  const std::uint64_t parkings = a->counters().blocked_by_faces + c->counters().blocked_by_faces;
  a->merge(std::move(*c));
  const std::uint64_t parked_again = a->counters().blocked_by_faces - parkings;
  const std::size_t still_parked = a->waiting_edge_count();
  EXPECT_LT(parked_again * 4, still_parked * 3) << parked_again << " parkings for " << still_parked << " parked edges";
}

TEST(TandemBlocks, MergesThatDoNotFitAreRefused) {
  const auto volume = blocks_test::sample(blocks_test::bodies(), kShape);
  CollectingSink sink;
  // Overlapping regions.
  auto a = quarter(*volume, 0, 0, sink);
  auto a2 = quarter(*volume, 0, 0, sink);
  EXPECT_THROW(a->merge(std::move(*a2)), InvalidArgument);
  // A surface still sweeping.
  const volume::Box cube = cube_cells(kShape);
  WorkingSurface sweeping(volume->geometry(), Region::block(cube, volume::Box{{32, 0, 0}, {64, 24, 48}}), 0, {}, &sink);
  EXPECT_THROW(a->merge(std::move(sweeping)), InvalidArgument);
  // Different options.
  TandemOptions options;
  options.axis = 0;
  options.simplify.max_error = 0.25;
  std::unique_ptr<WorkingSurface> other;
  extract_block(*volume, volume::Box{{32, 0, 0}, {64, 24, 48}}, options, &sink, &other);
  EXPECT_THROW(a->merge(std::move(*other)), InvalidArgument);
  // Along another axis.
  options.simplify = fine();
  options.axis = 2;
  extract_block(*volume, volume::Box{{32, 0, 0}, {64, 24, 48}}, options, &sink, &other);
  EXPECT_THROW(a->merge(std::move(*other)), InvalidArgument);
}

TEST(TandemBlocks, ProgressIsOneTaskOverLayersAndMerges) {
  class Counting final : public Progress {
  public:
    void begin(const std::string&, std::uint64_t t, const std::string&) override {
      ++begun;
      total = t;
      done_ = 0;
    }
    void update(std::uint64_t d) override { done_ = std::max(done_, d); }
    void end() override { ++ended; }
    std::uint64_t done() const { return done_; }
    int begun = 0, ended = 0;
    std::uint64_t total = 0;
  };
  const auto volume = blocks_test::sample(blocks_test::bodies(), kShape);
  Counting progress;
  TandemOptions options;
  options.progress = &progress;
  const BlocksStats stats = extract_blocks(*volume, cube_cells(kShape), 32, options, nullptr);
  EXPECT_EQ(progress.begun, 1);
  EXPECT_EQ(progress.ended, 1);
  // 8 leaves of 32 layers along i, 7 merges.
  EXPECT_EQ(progress.total, 8u * 32u + 7u);
  EXPECT_EQ(progress.done(), progress.total);
  EXPECT_EQ(stats.tandem.layers.size(), 8u * 32u);
  EXPECT_EQ(stats.tandem.counters.components_dumped, blocks_test::kBodies);
}

TEST(TandemBlocks, InvalidRequestsAreRefused) {
  const auto volume = blocks_test::sample(blocks_test::bodies(), kShape);
  TandemOptions options;
  EXPECT_THROW(extract_blocks(*volume, volume::Box{{0, 0, 0}, {65, 48, 48}}, 16, options, nullptr), InvalidArgument);
  options.simplify.isotropy = 2.0;
  EXPECT_THROW(extract_blocks(*volume, cube_cells(kShape), 16, options, nullptr), InvalidArgument);
}

} // namespace
} // namespace geotandem::tandem
