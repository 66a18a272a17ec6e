// The wire form of a working surface: a round trip in the middle of the sweep continues to the
// same components, a partial block surface comes back intact, and damaged records (a flipped
// byte, a cut, another version, another magic, a lying count) are refused with DataError.
#include <gtest/gtest.h>

#include <xxhash.h>

#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "blocks_support.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/tandem/serialize.hpp"

namespace geotandem::tandem {
namespace {

using blocks_test::kShape;
using fixtures::CollectingSink;

// One step of the tandem loop: extract(k); delay(k); activate(k); simplify; dumping.
void step(WorkingSurface& surface, const Layer& layer) {
  surface.add_layer(layer);
  surface.activate(static_cast<double>(layer.rank));
  surface.simplify();
  surface.dump();
}

fixtures::Input input() {
  return fixtures::Input(blocks_test::bodies(), kShape);
}

TEST(TandemSerialize, RoundTripInTheMiddleOfTheSweepContinuesToTheSameComponents) {
  const fixtures::Input in = input();
  const volume::Box cube = cube_cells(kShape);
  const volume::Geometry geometry = fixtures::test_geometry(kShape);
  for (int axis : {0, 2}) {
    SCOPED_TRACE("axis " + std::to_string(axis));
    // Without the round trip.
    CollectingSink plain_sink;
    {
      WorkingSurface surface(geometry, Region{}, axis, {}, &plain_sink);
      auto source = in.layers(cube, axis);
      run_tandem(*source, surface, TandemOptions{.axis = axis});
    }
    // With one in the middle: the surface then holds bodies cut by the front and waiting edges.
    CollectingSink sink;
    auto source = in.layers(cube, axis);
    auto surface = std::make_unique<WorkingSurface>(geometry, Region{}, axis, SimplifyOptions{}, &sink);
    Layer layer;
    for (int k = 0; k < 25 && source->next(layer); ++k)
      step(*surface, layer);
    ASSERT_GT(surface->triangle_count(), 0u);
    ASSERT_GT(surface->waiting_edge_count(), 0u);
    const std::vector<std::byte> record = serialize(*surface);
    auto copy = std::make_unique<WorkingSurface>(deserialize(record, &sink));
    EXPECT_EQ(copy->triangle_count(), surface->triangle_count());
    EXPECT_EQ(copy->vertex_count(), surface->vertex_count());
    EXPECT_EQ(copy->component_count(), surface->component_count());
    EXPECT_EQ(copy->waiting_edge_count(), surface->waiting_edge_count());
    EXPECT_EQ(copy->front(), surface->front());
    EXPECT_EQ(copy->region().blocks(), surface->region().blocks());
    EXPECT_EQ(copy->counters().collapses, surface->counters().collapses);
    EXPECT_EQ(copy->counters().components_dumped, surface->counters().components_dumped);
    const mesh::SurfaceMesh before = surface->snapshot(), after = copy->snapshot();
    EXPECT_EQ(before.points, after.points);
    EXPECT_EQ(before.triangles, after.triangles);
    EXPECT_EQ(serialize(*copy), record) << "a rebuilt surface writes the same record";
    EXPECT_EQ(serialize(std::move(*surface)), record) << "giving the surface up writes the same record";
    surface.reset();

    while (source->next(layer))
      step(*copy, layer);
    copy->finish();
    EXPECT_EQ(copy->triangle_count(), 0u);
    EXPECT_EQ(sink.components.size(), blocks_test::kBodies);
    blocks_test::expect_same_components(plain_sink.components, sink.components, 0.002, 0.01);
  }
}

TEST(TandemSerialize, PartialBlockSurfaceComesBackIntact) {
  const auto volume = blocks_test::sample(blocks_test::bodies(), kShape);
  CollectingSink sink;
  std::unique_ptr<WorkingSurface> surface;
  extract_block(*volume, volume::Box{{0, 0, 0}, {32, 48, 48}}, TandemOptions{}, &sink, &surface);
  ASSERT_GT(surface->triangle_count(), 0u);
  const std::vector<std::byte> record = serialize(*surface);
  EXPECT_GT(record.size(), kSurfaceWireHeaderSize);
  const WorkingSurface copy = deserialize(record, &sink);
  EXPECT_EQ(copy.region().blocks(), surface->region().blocks());
  EXPECT_EQ(copy.region().open_faces(), surface->region().open_faces());
  EXPECT_EQ(copy.waiting_edge_count(), surface->waiting_edge_count());
  EXPECT_EQ(copy.component_count(), surface->component_count());
  const mesh::SurfaceMesh a = surface->snapshot(), b = copy.snapshot();
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.triangles, b.triangles);
}

// A record of a small partial surface, to damage.
std::vector<std::byte> small_record() {
  const auto volume = blocks_test::sample(blocks_test::bodies(), kShape);
  std::unique_ptr<WorkingSurface> surface;
  extract_block(*volume, volume::Box{{0, 0, 0}, {32, 24, 24}}, TandemOptions{}, nullptr, &surface);
  return serialize(*surface);
}

// Expects DataError whose message contains `words`.
void expect_refused(const std::vector<std::byte>& record, const std::string& words) {
  try {
    deserialize(record, nullptr);
    ADD_FAILURE() << "a damaged record was accepted (expected: " << words << ")";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

void set_u32(std::vector<std::byte>& r, std::size_t at, std::uint32_t v) {
  std::memcpy(r.data() + at, &v, 4);
}
void set_u64(std::vector<std::byte>& r, std::size_t at, std::uint64_t v) {
  std::memcpy(r.data() + at, &v, 8);
}
void fix_checksum(std::vector<std::byte>& r) {
  set_u64(r, 24, XXH64(r.data() + kSurfaceWireHeaderSize, r.size() - kSurfaceWireHeaderSize, 0));
}

TEST(TandemSerialize, DamagedRecordsAreRefused) {
  const std::vector<std::byte> good = small_record();
  ASSERT_GT(good.size(), 1000u);
  EXPECT_NO_THROW(deserialize(good, nullptr));

  for (std::size_t at : {kSurfaceWireHeaderSize, good.size() / 2, good.size() - 1}) {
    SCOPED_TRACE("byte " + std::to_string(at));
    std::vector<std::byte> flipped = good;
    flipped[at] ^= std::byte{0x10};
    expect_refused(flipped, "checksum");
  }
  for (std::size_t keep : {std::size_t{0}, std::size_t{20}, kSurfaceWireHeaderSize, good.size() / 2, good.size() - 1}) {
    SCOPED_TRACE("cut at " + std::to_string(keep));
    expect_refused(std::vector<std::byte>(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(keep)), "truncated");
  }
  std::vector<std::byte> longer = good;
  longer.push_back(std::byte{0});
  expect_refused(longer, "trailing");

  std::vector<std::byte> version = good;
  set_u32(version, 8, kSurfaceWireVersion + 1);
  expect_refused(version, "format version " + std::to_string(kSurfaceWireVersion + 1) + ", this build reads " +
                              std::to_string(kSurfaceWireVersion));

  std::vector<std::byte> magic = good;
  magic[0] = std::byte{'X'};
  expect_refused(magic, "magic");

  // A consistent checksum over a payload that lies: the decoder still refuses it. The count of
  // components follows the geometry (121 bytes), axis (4), options (25), region (cube 48, count 8,
  // one block 48), front, last rank (16), origin (24) and counters (112).
  const std::size_t components_at = kSurfaceWireHeaderSize + 121 + 4 + 25 + 48 + 8 + 48 + 16 + 24 + 112;
  std::vector<std::byte> lying = good;
  set_u64(lying, components_at, std::uint64_t{1} << 40);
  fix_checksum(lying);
  expect_refused(lying, "does not fit");

  std::uint64_t components = 0;
  std::memcpy(&components, good.data() + components_at, 8);
  const std::size_t first_vertex = components_at + 8 + 8 * components + 8;
  std::vector<std::byte> not_finite = good;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(not_finite.data() + first_vertex, &nan, 8);
  fix_checksum(not_finite);
  expect_refused(not_finite, "non-finite position");

  std::vector<std::byte> axis = good;
  set_u32(axis, kSurfaceWireHeaderSize + 121, 7);
  fix_checksum(axis);
  expect_refused(axis, "axis 7");
}

} // namespace
} // namespace geotandem::tandem
