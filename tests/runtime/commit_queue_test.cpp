// The manager's index writes on their own thread (src/commit_queue.hpp): in order, an action
// queued after commits sees them in the index, nothing after a failed commit is done, and what is
// queued is committed even when the manager stops without draining (Ctrl-C, an error).
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>

#include "../../framework/runtime/src/commit_queue.hpp"
#include "fixtures.hpp"
#include "geotandem/store/shard.hpp"
#include "scratch.hpp"

namespace geotandem::runtime::detail {
namespace {

using geotandem::testing::ScratchDir;

struct Batch {
  std::vector<store::IndexEntry> entries;
  std::vector<std::uint64_t> keys;
};

// Components written (and synced) to a worker's shard, as a worker does before its COMMIT.
Batch write(store::ShardWriter& writer, const volume::Geometry& g, std::uint64_t first, int n) {
  Batch b;
  for (int i = 0; i < n; ++i) {
    const mesh::Component c = store::testing::make_component(first + static_cast<std::uint64_t>(i), g);
    store::IndexEntry e;
    e.key = c.key;
    e.location = writer.append(c);
    e.stats = c.stats;
    b.entries.push_back(std::move(e));
    b.keys.push_back(c.key);
  }
  writer.sync();
  return b;
}

// A store, a worker's shard writer, and the manager's committer.
struct Stores {
  ScratchDir dir;
  volume::Geometry g = store::testing::test_geometry();
  store::ComponentStore store = store::ComponentStore::create(dir.path() / "store", g);
  store::ShardWriter writer{dir.path() / "store", "w1", g};
  ComponentCommitter committer{store};
};

TEST(CommitQueue, AnActionRunsAfterTheCommitsQueuedBeforeIt) {
  Stores f;
  auto& [dir, g, store, writer, committer] = f;
  CommitQueue queue(committer);
  std::atomic<std::size_t> seen{0};
  std::vector<std::uint64_t> all;
  for (int batch = 0; batch < 20; ++batch) {
    Batch b = write(writer, g, 1000 + 50 * static_cast<std::uint64_t>(batch), 30);
    all.insert(all.end(), b.keys.begin(), b.keys.end());
    queue.commit(std::move(b.entries));
    // Run on the queue's thread: every key committed so far must be in the index already.
    queue.then([&store, &seen, expected = all] {
      if (store.present(expected).size() == expected.size()) ++seen;
    });
  }
  queue.drain();
  EXPECT_EQ(seen.load(), 20u);
  EXPECT_EQ(committer.added(), all.size());
  EXPECT_EQ(store.size(), all.size());
  // The same keys again (a retried task): duplicates, nothing added.
  Batch again = write(writer, g, 1000, 30);
  queue.commit(std::move(again.entries));
  queue.drain();
  EXPECT_EQ(committer.duplicates(), 30u);
  EXPECT_EQ(store.size(), all.size());
}

TEST(CommitQueue, NothingQueuedAfterAFailedCommitIsDone) {
  Stores f;
  auto& [dir, g, store, writer, committer] = f;
  CommitQueue queue(committer);
  Batch good = write(writer, g, 1, 5);
  Batch bad = write(writer, g, 100, 5);
  bad.entries[2].location.length += 1; // disagrees with its counts: the store refuses the batch
  Batch later = write(writer, g, 200, 5);
  bool recorded = false;
  queue.commit(std::move(good.entries));
  queue.commit(std::move(bad.entries));
  queue.then([&recorded] { recorded = true; });
  queue.commit(std::move(later.entries));
  EXPECT_THROW(queue.drain(), InvalidArgument);
  EXPECT_THROW(queue.rethrow_failure(), InvalidArgument);
  EXPECT_FALSE(recorded) << "leaves were recorded finished after their components failed to commit";
  EXPECT_EQ(store.present(good.keys).size(), 5u);
  EXPECT_TRUE(store.present(bad.keys).empty());
  EXPECT_TRUE(store.present(later.keys).empty());
}

TEST(CommitQueue, WhatIsQueuedIsCommittedWhenTheManagerStopsWithoutDraining) {
  Stores f;
  auto& [dir, g, store, writer, committer] = f;
  std::vector<std::uint64_t> all;
  {
    CommitQueue queue(committer);
    for (int batch = 0; batch < 10; ++batch) {
      Batch b = write(writer, g, 10 + 20 * static_cast<std::uint64_t>(batch), 20);
      all.insert(all.end(), b.keys.begin(), b.keys.end());
      queue.commit(std::move(b.entries));
    }
  }
  EXPECT_EQ(store.present(all).size(), all.size());
}

} // namespace
} // namespace geotandem::runtime::detail
