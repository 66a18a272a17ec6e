// Boxes larger than Attribute::kTile are computed tile by tile; the result must not show the seams.

#include <gtest/gtest.h>

#include "fixtures.hpp"
#include "geotandem/attributes/catalog.hpp"

namespace geotandem::attributes {
namespace {

using testing::cube;
using testing::noise;

// Reads `attribute` in slabs of `step` samples along `axis` (each far below the tile size) and
// compares them with one read of the whole cube, which the attribute splits into tiles.
void expect_whole_equals_slabs(const Attribute& attribute, int axis, std::int64_t step) {
  const Box bounds = attribute.geometry().bounds();
  ASSERT_GT(Attribute::tiles_along(bounds.size(axis), axis), 1) << "the cube must need several tiles";
  const std::vector<float> whole = attribute.read(bounds);
  for (std::int64_t lo = 0; lo < bounds.hi[axis]; lo += step) {
    Box slab = bounds;
    slab.lo[axis] = lo;
    slab.hi[axis] = std::min(lo + step, bounds.hi[axis]);
    const std::vector<float> part = attribute.read(slab);
    for (auto i = slab.lo[0]; i < slab.hi[0]; ++i)
      for (auto j = slab.lo[1]; j < slab.hi[1]; ++j)
        for (auto k = slab.lo[2]; k < slab.hi[2]; ++k)
          ASSERT_EQ(part[slab.offset({i, j, k})], whole[bounds.offset({i, j, k})])
              << attribute.name() << " at (" << i << ", " << j << ", " << k << ")";
  }
}

TEST(Tiling, WholeCubeReadInTilesEqualsSmallBoxes) {
  auto wide = cube({2 * Attribute::kTile[0] + 7, 5, 20}, [](int i, int j, int k) { return noise(i, j, k); });
  auto deep = cube({3, 4, 2 * Attribute::kTile[2] + 45}, [](int i, int j, int k) { return noise(i, j, k, 3); });
  for (const AttributeSpec& spec : builtin_attributes()) {
    std::vector<VolumePtr> on_wide(static_cast<std::size_t>(spec.inputs), wide);
    std::vector<VolumePtr> on_deep(static_cast<std::size_t>(spec.inputs), deep);
    expect_whole_equals_slabs(*make_attribute(spec.name, on_wide), 0, 9);
    expect_whole_equals_slabs(*make_attribute(spec.name, on_deep), 2, 37);
  }
}

// What the extraction does (framework/tandem, McOptions::slab_samples): a block of cells [lo, hi)
// reads samples [lo, hi + 1) in slabs of consecutive cross-sections along its axis. Blocks touching
// the cube's faces (mirrored halos) and interior ones, slabs of 1, 7 and all sections, and a block
// long enough on its axis that a slab of all sections is cut into tiles: every sample equals the
// whole-cube computation bit for bit, for every attribute and for the quickstart's chain.
TEST(Tiling, BlockSlabsAtCubeEdgesEqualTheWholeCube) {
  const Index3 shape{2 * Attribute::kTile[0] + 7, 23, 29};
  auto u = cube(shape, [](int i, int j, int k) { return std::cos(0.4 * k + 0.05 * i) + noise(i, j, k, 5); });
  std::vector<std::shared_ptr<const volume::Volume>> attributes;
  for (const AttributeSpec& spec : builtin_attributes())
    attributes.push_back(make_attribute(spec.name, std::vector<VolumePtr>(static_cast<std::size_t>(spec.inputs), u)));
  auto envelope = make_attribute("envelope", {u});
  attributes.push_back(
      make_attribute("product", {make_attribute("chaos", {u}), make_attribute("normalise", {envelope})}));
  // Blocks of cells: at the near faces, at the far faces, in the middle (cells run to shape - 1).
  const std::vector<Box> blocks = {Box{{0, 0, 0}, {shape[0] - 1, 12, 15}},
                                   Box{{40, 10, 14}, {shape[0] - 1, shape[1] - 1, shape[2] - 1}},
                                   Box{{30, 5, 6}, {100, 17, 22}}};
  for (const auto& attribute : attributes) {
    const Box bounds = attribute->geometry().bounds();
    const std::vector<float> whole = attribute->read(bounds);
    for (int axis = 0; axis < 3; ++axis)
      for (const Box& cells : blocks) {
        const Box samples{cells.lo, {cells.hi[0] + 1, cells.hi[1] + 1, cells.hi[2] + 1}};
        for (const std::int64_t per_slab : {std::int64_t{1}, std::int64_t{7}, samples.size(axis)}) {
          for (std::int64_t lo = samples.lo[axis]; lo < samples.hi[axis]; lo += per_slab) {
            Box slab = samples;
            slab.lo[axis] = lo;
            slab.hi[axis] = std::min(lo + per_slab, samples.hi[axis]);
            const std::vector<float> part = attribute->read(slab);
            for (auto i = slab.lo[0]; i < slab.hi[0]; ++i)
              for (auto j = slab.lo[1]; j < slab.hi[1]; ++j)
                for (auto k = slab.lo[2]; k < slab.hi[2]; ++k)
                  ASSERT_EQ(part[slab.offset({i, j, k})], whole[bounds.offset({i, j, k})])
                      << attribute->source() << ": block " << cells.to_string() << ", axis " << axis << ", slab "
                      << slab.to_string() << " at (" << i << ", " << j << ", " << k << ")";
          }
        }
      }
  }
}

// Tiles stay within 5/4 of the nominal size, and a box just over one tile is not cut into a full
// tile and a sliver (a block of 129 samples is two tiles of 64 and 65, not 64, 64 and 1).
TEST(Tiling, TilesAreBalancedAndBounded) {
  for (int axis = 0; axis < 3; ++axis) {
    const std::int64_t nominal = Attribute::kTile[axis];
    EXPECT_EQ(Attribute::tiles_along(1, axis), 1);
    EXPECT_EQ(Attribute::tiles_along(nominal + nominal / 4, axis), 1);
    EXPECT_EQ(Attribute::tiles_along(nominal + nominal / 4 + 1, axis), 2);
    EXPECT_EQ(Attribute::tiles_along(2 * nominal + 1, axis), 2);
    for (std::int64_t n = 1; n < 9 * nominal; n += 7) {
      const std::int64_t m = Attribute::tiles_along(n, axis);
      EXPECT_LE((n + m - 1) / m, nominal + nominal / 4) << "n = " << n;
      if (m > 1) {
        EXPECT_GE(n / m, nominal / 2) << "n = " << n; // no sliver beside full tiles
      } else {
        EXPECT_LE(n, nominal + nominal / 4) << "n = " << n;
      }
    }
  }
}

} // namespace
} // namespace geotandem::attributes
