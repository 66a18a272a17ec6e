// extract_block: one block of a volume from marching cubes to the sink, with the surface that waits
// for a neighbour handed back, progress reported per layer, and invalid requests refused.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <thread>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/quality.hpp"
#include "geotandem/mesh/topology.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "simplify_fixtures.hpp"
#include "spare_meshes.hpp"

namespace geotandem::tandem {
namespace {

// Counts what a run reports.
class CountingProgress final : public Progress {
public:
  void begin(const std::string&, std::uint64_t total, const std::string& unit) override {
    ++begun;
    this->total = total;
    this->unit = unit;
    done_ = 0;
  }
  void update(std::uint64_t done) override { done_ = std::max(done_, done); }
  void end() override { ++ended; }
  std::uint64_t done() const { return done_; }
  int begun = 0, ended = 0;
  std::uint64_t total = 0;
  std::string unit;
};

// A cube of 48 x 24 x 24 samples; the block is the cells with i < 30. One ball lies inside the
// block, far enough from the open face i = 30 for every collapse's ball to stay clear of it (a
// body near an open face waits for the neighbour even when it does not touch the face); the other
// ball crosses the face.
std::unique_ptr<volume::MemoryVolume> two_balls() {
  const fixtures::Field inside = fixtures::sphere({9.3, 11.7, 12.2}, 5.0);
  const fixtures::Field crossing = fixtures::sphere({30.4, 12.2, 11.6}, 6.0);
  volume::Geometry g = fixtures::test_geometry({48, 24, 24});
  std::vector<float> samples(g.bounds().count());
  for (std::int64_t i = 0; i < 48; ++i)
    for (std::int64_t j = 0; j < 24; ++j)
      for (std::int64_t k = 0; k < 24; ++k) {
        const double x = static_cast<double>(i), y = static_cast<double>(j), z = static_cast<double>(k);
        samples[g.bounds().offset({i, j, k})] = static_cast<float>(std::max(inside(x, y, z), crossing(x, y, z)));
      }
  return std::make_unique<volume::MemoryVolume>(g, std::move(samples), "two balls");
}

const volume::Box kBlock{{0, 0, 0}, {30, 23, 23}};

TEST(TandemBlock, FinishedBodiesGoToTheSinkTheRestWaits) {
  const auto volume = two_balls();
  for (bool brute : {false, true}) {
    SCOPED_TRACE(brute ? "brute force" : "tandem");
    fixtures::CollectingSink sink;
    CountingProgress progress;
    TandemOptions options;
    options.axis = 0;
    options.progress = &progress;
    std::unique_ptr<WorkingSurface> remaining;
    const TandemStats stats = extract_block(*volume, kBlock, options, &sink, &remaining, brute);
    ASSERT_EQ(sink.components.size(), 1u) << "only the ball inside the block is finished";
    const mesh::Component& c = sink.components[0];
    EXPECT_TRUE(mesh::check_topology(c.surface).is_closed_manifold());
    EXPECT_TRUE(c.stats.closed);
    EXPECT_NEAR(mesh::enclosed_volume(c.surface) / (4.0 / 3.0 * M_PI * 125.0), 1.0, 0.05);
    ASSERT_TRUE(remaining);
    EXPECT_GT(remaining->triangle_count(), 0u);
    EXPECT_EQ(remaining->component_count(), 1u);
    EXPECT_EQ(stats.remaining_triangles, remaining->triangle_count());
    EXPECT_EQ(stats.layers.size(), 30u);
    EXPECT_EQ(progress.begun, 1);
    EXPECT_EQ(progress.ended, 1);
    EXPECT_EQ(progress.total, 30u);
    EXPECT_EQ(progress.done(), 30u);
    EXPECT_EQ(progress.unit, "layers");
    // The vertices the neighbour will weld to are still the marching-cubes vertices.
    const mesh::SurfaceMesh full = extract_surface(*volume, kBlock, McOptions{0.0f, 0});
    const mesh::SurfaceMesh kept = remaining->snapshot();
    std::size_t on_face = 0, found = 0;
    for (const auto& p : full.points) {
      if (p[0] != 30.0) continue;
      ++on_face;
      for (const auto& q : kept.points)
        if (q == p) {
          ++found;
          break;
        }
    }
    EXPECT_GT(on_face, 10u);
    EXPECT_EQ(found, on_face);
  }
}

// What a block run gives: the components in the order they were committed, what waits, and the
// collapses made.
struct Outcome {
  std::vector<mesh::Component> components;
  mesh::SurfaceMesh remaining;
  std::uint64_t collapses = 0;
};

// The two balls with noise on top: many small bodies, so a surface whose storage is larger than
// the two balls' alone.
std::unique_ptr<volume::MemoryVolume> noisy_balls(unsigned seed) {
  const auto clean = two_balls();
  std::vector<float> samples(clean->geometry().bounds().count());
  clean->read(clean->geometry().bounds(), samples);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> jitter(-0.9f, 0.9f);
  for (float& v : samples)
    v += jitter(rng);
  return std::make_unique<volume::MemoryVolume>(clean->geometry(), std::move(samples), "noisy balls");
}

// With keep_surface_storage() on (as in a worker), a surface takes over the mesh storage the last
// one destroyed on its thread left (emptied, the room kept): what it gives never depends on what
// came before. Each run, one block or two merged, gives the same components, the same surface
// waiting and the same collapses as on a thread of its own, after a larger surface of another
// field, a smaller one, or the same cells of another field. Off (the default), nothing is kept.
TEST(TandemBlock, ASurfaceAfterAnotherOnTheSameThreadGivesWhatItsOwnThreadGives) {
  const auto clean = two_balls();
  const auto noisy = noisy_balls(5), other = noisy_balls(6);
  const volume::Box all = cube_cells(clean->geometry().shape);
  const volume::Box rest{{30, 0, 0}, {47, 23, 23}}; // kBlock's brother
  auto block = [](const volume::Volume& v, const volume::Box& cells, fixtures::CollectingSink& sink) {
    TandemOptions options;
    options.axis = 0;
    std::unique_ptr<WorkingSurface> remaining;
    extract_block(v, cells, options, &sink, &remaining);
    return remaining;
  };
  // One block, or (merged) kBlock and its brother, then finished.
  auto run = [&](const volume::Volume& v, const volume::Box& cells, bool merged) {
    fixtures::CollectingSink sink;
    Outcome out;
    std::unique_ptr<WorkingSurface> surface = block(v, merged ? kBlock : cells, sink);
    if (merged) {
      std::unique_ptr<WorkingSurface> brother = block(v, rest, sink);
      out.collapses += brother->counters().collapses;
      surface->merge(std::move(*brother));
      brother.reset();
      out.remaining = surface->snapshot();
      surface->finish();
    } else {
      out.remaining = surface->snapshot();
    }
    out.collapses += surface->counters().collapses;
    out.components = std::move(sink.components);
    return out;
  };
  auto alone = [&](const volume::Volume& v, const volume::Box& cells, bool merged) {
    Outcome out;
    std::thread([&] { out = run(v, cells, merged); }).join();
    return out;
  };
  struct Step {
    const volume::Volume* volume;
    volume::Box cells;
    bool merged;
  };
  const Step steps[] = {{noisy.get(), all, false},    {clean.get(), kBlock, false}, {other.get(), all, false},
                        {noisy.get(), kBlock, false}, {other.get(), all, true},     {clean.get(), all, true},
                        {noisy.get(), all, true},     {other.get(), kBlock, false}};
  {
    fixtures::CollectingSink sink;
    block(*noisy, all, sink).reset();
    EXPECT_EQ(detail::spare_surface_storage_bytes(), 0u) << "kept while off";
  }
  keep_surface_storage(true);
  std::size_t n = 0;
  for (const Step& step : steps) {
    const Outcome want = alone(*step.volume, step.cells, step.merged);
    const bool reused = detail::spare_surface_storage_bytes() > 0;
    EXPECT_EQ(reused, n > 0) << "step " << n << ": the storage the last step left";
    const Outcome got = run(*step.volume, step.cells, step.merged);
    const std::string where = "step " + std::to_string(n);
    ASSERT_EQ(got.components.size(), want.components.size()) << where;
    EXPECT_GT(want.components.size() + want.remaining.triangles.size(), 0u) << where;
    for (std::size_t k = 0; k < got.components.size(); ++k) {
      EXPECT_EQ(got.components[k].key, want.components[k].key) << where << ", component " << k;
      EXPECT_EQ(got.components[k].surface.points, want.components[k].surface.points) << where << ", component " << k;
      EXPECT_EQ(got.components[k].surface.triangles, want.components[k].surface.triangles)
          << where << ", component " << k;
    }
    EXPECT_EQ(got.remaining.points, want.remaining.points) << where;
    EXPECT_EQ(got.remaining.triangles, want.remaining.triangles) << where;
    EXPECT_EQ(got.collapses, want.collapses) << where;
    ++n;
  }
  EXPECT_GT(detail::spare_surface_storage_bytes(), 0u);
  release_surface_storage();
  EXPECT_EQ(detail::spare_surface_storage_bytes(), 0u);
  {
    fixtures::CollectingSink sink;
    block(*noisy, all, sink).reset();
  }
  EXPECT_GT(detail::spare_surface_storage_bytes(), 0u);
  keep_surface_storage(false);
  EXPECT_EQ(detail::spare_surface_storage_bytes(), 0u);
}

// A merge adds every counter of the other side to the surface's (a merge once dropped the other
// side's distance-bound refusals); the merge's own simplification of the seam only adds more.
TEST(TandemBlock, AMergeAddsEveryCounterOfTheOtherSide) {
  const auto noisy = noisy_balls(5);
  const volume::Box rest{{30, 0, 0}, {47, 23, 23}}; // kBlock's brother
  TandemOptions options;
  options.axis = 0;
  fixtures::CollectingSink sink;
  std::unique_ptr<WorkingSurface> surface, brother;
  extract_block(*noisy, kBlock, options, &sink, &surface);
  extract_block(*noisy, rest, options, &sink, &brother);
  const SimplifyCounters mine = surface->counters(), theirs = brother->counters();
  ASSERT_GT(theirs.rejected_distance, 0u);
  ASSERT_GT(theirs.collapses, 0u);
  surface->merge(std::move(*brother));
  const SimplifyCounters merged = surface->counters();
  EXPECT_EQ(merged.input_triangles, mine.input_triangles + theirs.input_triangles);
  for (std::size_t i = 0; i < SimplifyCounters::all.size(); ++i) {
    const auto field = SimplifyCounters::all[i];
    EXPECT_GE(merged.*field, mine.*field + theirs.*field) << "counter " << i << " of SimplifyCounters::all";
  }
}

TEST(TandemBlock, InvalidRequestsAreRefused) {
  const auto volume = two_balls();
  fixtures::CollectingSink sink;
  TandemOptions options;
  options.axis = 3;
  EXPECT_THROW(extract_block(*volume, kBlock, options, &sink), InvalidArgument);
  options.axis = 0;
  EXPECT_THROW(extract_block(*volume, volume::Box{{0, 0, 0}, {48, 23, 23}}, options, &sink), InvalidArgument);
  options.simplify.max_error = -1.0;
  EXPECT_THROW(extract_block(*volume, kBlock, options, &sink), InvalidArgument);
}

} // namespace
} // namespace geotandem::tandem
