// extract_block: one block of a volume from marching cubes to the sink, with the surface that waits
// for a neighbour handed back, progress reported per layer, and invalid requests refused.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/quality.hpp"
#include "geotandem/mesh/topology.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "simplify_fixtures.hpp"

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
