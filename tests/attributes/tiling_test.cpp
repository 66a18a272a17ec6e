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
  ASSERT_GT(bounds.size(axis), Attribute::kTile[axis]) << "the cube must need several tiles";
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
  auto wide = cube({Attribute::kTile[0] + 7, 5, 20}, [](int i, int j, int k) { return noise(i, j, k); });
  auto deep = cube({3, 4, Attribute::kTile[2] + 45}, [](int i, int j, int k) { return noise(i, j, k, 3); });
  for (const AttributeSpec& spec : builtin_attributes()) {
    std::vector<VolumePtr> on_wide(static_cast<std::size_t>(spec.inputs), wide);
    std::vector<VolumePtr> on_deep(static_cast<std::size_t>(spec.inputs), deep);
    expect_whole_equals_slabs(*make_attribute(spec.name, on_wide), 0, 9);
    expect_whole_equals_slabs(*make_attribute(spec.name, on_deep), 2, 37);
  }
}

} // namespace
} // namespace geotandem::attributes
