// merge_record: a partial surface merged straight from its wire form gives the components of a
// merge of the rebuilt surface, and a record that does not fit is refused without a change.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "blocks_support.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/tandem/block_tree.hpp"
#include "geotandem/tandem/serialize.hpp"
#include "geotandem/tandem/tandem.hpp"

namespace geotandem::tandem {
namespace {

using blocks_test::kShape;
using fixtures::CollectingSink;

std::vector<mesh::Component> fold(const volume::Volume& v, bool from_record) {
  CollectingSink sink;
  const BlockTree tree(cube_cells(kShape), 24);
  TandemOptions options;
  options.simplify.max_error = blocks_test::kMaxError;
  std::unique_ptr<WorkingSurface> all;
  for (NodeId leaf : tree.leaves()) {
    std::unique_ptr<WorkingSurface> piece;
    extract_block(v, tree.node(leaf).cells, options, &sink, &piece);
    if (!all) {
      all = std::move(piece);
      continue;
    }
    const std::vector<std::byte> record = serialize(*piece);
    if (from_record)
      merge_record(*all, record);
    else
      all->merge(deserialize(record, &sink));
  }
  all->finish();
  return blocks_test::by_key(sink.components);
}

TEST(TandemMergeRecord, SameComponentsAsMergingTheRebuiltSurface) {
  const auto v = blocks_test::sample(blocks_test::bodies(), kShape);
  const auto a = fold(*v, false), b = fold(*v, true);
  ASSERT_GE(a.size(), blocks_test::kBodies);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].key, b[i].key);
    EXPECT_NEAR(a[i].stats.volume, b[i].stats.volume, 0.005 * std::abs(a[i].stats.volume) + 1e-9);
    EXPECT_EQ(a[i].stats.closed, b[i].stats.closed);
  }
}

TEST(TandemMergeRecord, ARecordThatDoesNotFitIsRefusedWithoutAChange) {
  const auto v = blocks_test::sample(blocks_test::bodies(), kShape);
  const BlockTree tree(cube_cells(kShape), 32);
  CollectingSink sink;
  std::unique_ptr<WorkingSurface> a;
  extract_block(*v, tree.node(tree.leaves()[0]).cells, TandemOptions{}, &sink, &a);
  const std::vector<std::byte> same = serialize(*a);
  const std::size_t before = a->triangle_count();
  EXPECT_THROW(merge_record(*a, same), DataError); // the same block twice: the regions overlap
  EXPECT_EQ(a->triangle_count(), before);
  std::vector<std::byte> cut(same.begin(), same.begin() + static_cast<long>(same.size() / 2));
  EXPECT_THROW(merge_record(*a, cut), DataError);
  EXPECT_EQ(a->triangle_count(), before);
}

} // namespace
} // namespace geotandem::tandem
