// A reader beside an open writer: what it sees of each commit, through size(), read() and the
// statement contains() keeps between calls.

#include <gtest/gtest.h>

#include "fixtures.hpp"
#include "geotandem/store/local_sink.hpp"
#include "geotandem/store/store.hpp"
#include "scratch.hpp"

namespace geotandem::store {
namespace {

using geotandem::testing::ScratchDir;
using testing::make_component;
using testing::test_geometry;

TEST(Store, ReaderSeesCommittedRowsWhileAWriterIsOpen) {
  ScratchDir scratch;
  auto dir = scratch.path() / "store";
  auto store = ComponentStore::create(dir, test_geometry());
  LocalSink sink(store, {"local", std::nullopt, 1});
  sink.commit(make_component(1, test_geometry()));
  auto reader = ComponentStore::open(dir);
  EXPECT_EQ(reader.size(), 1u);
  sink.commit(make_component(2, test_geometry()));
  EXPECT_EQ(reader.size(), 2u);
  EXPECT_NO_THROW(reader.read(2));
}

// contains() keeps its statement between calls: it must answer from the index as it is now (no
// snapshot held from an earlier call), in the writer and in a reader.
TEST(Store, ContainsSeesEveryCommitInTheWriterAndInAReader) {
  ScratchDir scratch;
  auto dir = scratch.path() / "store";
  auto store = ComponentStore::create(dir, test_geometry());
  auto reader = ComponentStore::open(dir);
  LocalSink sink(store, {"local", std::nullopt, 1});
  for (std::uint64_t key = 1; key <= 5; ++key) {
    EXPECT_FALSE(store.contains(key)) << key;
    EXPECT_FALSE(reader.contains(key)) << key;
    sink.commit(make_component(key, test_geometry()));
    EXPECT_TRUE(store.contains(key)) << key;
    EXPECT_TRUE(reader.contains(key)) << key;
    sink.commit(make_component(key + 100, test_geometry())); // after a "yes" in the reader
    EXPECT_EQ(reader.size(), 2 * key) << key;
    EXPECT_TRUE(reader.contains(key + 100)) << key;
  }
}

} // namespace
} // namespace geotandem::store
