// The manager's decisions (algorithm 6) fed with events, without sockets: a replay of the seed's
// figure 10 (three workers, eight blocks), one worker alone, and the restricted adjacency of the
// seed's figure 8. Random event orders are in schedule_properties_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>

#include "geotandem/runtime/schedule.hpp"
#include "geotandem/tandem/block_tree.hpp"
#include "schedule_support.hpp"

namespace geotandem::runtime {
namespace {

using schedule_test::cells;
using tandem::BlockTree;
using tandem::NodeId;

// A cube of 32^3 cells with leaves of 16: eight blocks, cut along x (left 1, right 8), then y
// (up/down), then z (front/back). Leaves in tree order: 3 4 6 7 10 11 13 14.
TEST(Schedule, Figure10ReplayWithThreeWorkers) {
  const BlockTree tree(cells(32, 32, 32), 16);
  ASSERT_EQ(tree.leaves(), (std::vector<NodeId>{3, 4, 6, 7, 10, 11, 13, 14}));
  Schedule s(tree);
  for (WorkerId w : {1u, 2u, 3u})
    s.join(w);
  auto expect = [&](WorkerId w, TaskKind kind, NodeId leaf = tandem::kNoNode, WorkerId target = 0) {
    const Decision d = s.next(w);
    EXPECT_EQ(d.kind, kind) << "worker " << w << " got " << to_string(d.kind);
    if (kind == TaskKind::extract) {
      EXPECT_EQ(d.leaf, leaf) << "worker " << w;
    }
    if (kind == TaskKind::send) {
      EXPECT_EQ(d.target, target) << "worker " << w;
    }
    return d;
  };
  // W1 ? -> EXTRACT 3; W2 ? -> EXTRACT 4; W3 ? -> EXTRACT 6 (nobody holds anything yet).
  expect(1, TaskKind::extract, 3);
  expect(2, TaskKind::extract, 4);
  expect(3, TaskKind::extract, 6);
  // W1 has leaf 3; W2 works on its brother 4: W1 ? -> SEND W2, then EXTRACT 7.
  s.done(1);
  const Decision send1 = expect(1, TaskKind::send, tandem::kNoNode, 2);
  EXPECT_TRUE(s.arrived(1, send1.transfer));
  expect(1, TaskKind::extract, 7);
  // W2 ? -> MERGE (3 arrived): W2 holds node 2 = {3, 4}.
  s.done(2);
  expect(2, TaskKind::merge);
  s.done(2);
  EXPECT_EQ(s.leaves_held(2), 2u);
  // W3 has leaf 6 (down-front under left). Node 2 (up) passes the restricted adjacency with leaf 6,
  // and so does W1's leaf 7 (its brother); the larger aggregate receives: W3 ? -> SEND W2.
  s.done(3);
  const Decision send3 = expect(3, TaskKind::send, tandem::kNoNode, 2);
  EXPECT_TRUE(s.arrived(3, send3.transfer));
  // W3 ? -> EXTRACT 10: W3 holds nothing, so the first unprocessed leaf.
  expect(3, TaskKind::extract, 10);
  // W2 ? -> MERGE 6: W2 holds {3, 4, 6}.
  expect(2, TaskKind::merge);
  s.done(2);
  // W2 holds {3,4,6}; W1 extracts 7, adjacent but smaller: the smaller side travels, so W2 does
  // not send. No unprocessed leaf is adjacent to {2, 6}: W2 ? -> EXTRACT 11, the first left.
  expect(2, TaskKind::extract, 11);
  // W1 has 7 (brother of 6, held by W2, which claims 4 leaves): W1 ? -> SEND W2, then EXTRACT 13.
  s.done(1);
  const Decision send1b = expect(1, TaskKind::send, tandem::kNoNode, 2);
  EXPECT_TRUE(s.arrived(1, send1b.transfer));
  expect(1, TaskKind::extract, 13);
  // W3 has 10: node 1 (the whole left half, now claimed by W2) passes the test with it (ancestry
  // {10, 9}: front, up, none opposite to left), and 11 is its brother: W3 ? -> SEND W2, EXTRACT 14.
  s.done(3);
  const Decision send3b = expect(3, TaskKind::send, tandem::kNoNode, 2);
  EXPECT_TRUE(s.arrived(3, send3b.transfer));
  expect(3, TaskKind::extract, 14);
  // W2 finishes 11 and merges both surfaces waiting for it.
  s.done(2);
  expect(2, TaskKind::merge);
  s.done(2);
  expect(2, TaskKind::merge);
  s.done(2);
  EXPECT_EQ(s.leaves_held(2), 6u);
  // Its neighbours W1 (13) and W3 (14) are smaller and nothing is left to extract: W2 ? -> WAIT.
  expect(2, TaskKind::wait);
  EXPECT_EQ(s.unprocessed(), 0u);
  // W1 has 13 (adjacent to node 9 of W2, and brother of W3's 14): the larger wins, SEND W2.
  s.done(1);
  const Decision send1c = expect(1, TaskKind::send, tandem::kNoNode, 2);
  EXPECT_TRUE(s.arrived(1, send1c.transfer));
  s.done(3);
  const Decision send3c = expect(3, TaskKind::send, tandem::kNoNode, 2);
  EXPECT_TRUE(s.arrived(3, send3c.transfer));
  // W1 and W3 hold nothing and nothing is left: they wait until the run is complete.
  expect(1, TaskKind::wait);
  expect(3, TaskKind::wait);
  expect(2, TaskKind::merge);
  s.done(2);
  expect(2, TaskKind::merge);
  s.done(2);
  EXPECT_EQ(s.leaves_held(2), 8u);
  // W2 holds the whole surface: FINISHED (final); then everyone is told FINISHED.
  const Decision last = expect(2, TaskKind::finished);
  EXPECT_TRUE(last.final);
  EXPECT_FALSE(s.complete());
  s.done(2);
  EXPECT_TRUE(s.complete());
  EXPECT_EQ(s.counts().extract, 8u);
  EXPECT_EQ(s.counts().send, 6u);
  EXPECT_EQ(s.counts().merge, 6u); // with one extraction into a held surface (11): 7 joins in all
  for (WorkerId w : {1u, 2u, 3u}) {
    const Decision d = s.next(w);
    EXPECT_EQ(d.kind, TaskKind::finished);
    EXPECT_FALSE(d.final);
  }
}

TEST(Schedule, OneWorkerProcessesAndAggregatesEverything) {
  const BlockTree tree(cells(40, 24, 16), 8);
  Schedule s(tree);
  s.join(7);
  std::size_t extracts = 0;
  for (int i = 0; i < 1000 && !s.complete(); ++i) {
    const Decision d = s.next(7);
    ASSERT_NE(d.kind, TaskKind::send) << "a lone worker has nobody to send to";
    ASSERT_NE(d.kind, TaskKind::wait) << "a lone worker never waits";
    extracts += d.kind == TaskKind::extract;
    s.done(7);
  }
  EXPECT_TRUE(s.complete());
  EXPECT_EQ(extracts, tree.leaves().size());
}

TEST(Schedule, RestrictedAdjacencyOfTheSeedsFigure8) {
  // The seed's example: leaf 6 passes the test against n13, leaf 7 does not. Here with a cube cut
  // x, y, y: node 1 (left) against the leaves under 8 (right).
  const BlockTree tree(cells(32, 32, 16), 16);
  Aggregate left(tree);
  for (NodeId leaf : tree.leaves())
    if (tree.is_ancestor(1, leaf)) left.add(leaf);
  EXPECT_EQ(left.maximal_nodes(), std::vector<NodeId>{1});
  for (NodeId leaf : tree.leaves()) {
    if (tree.is_ancestor(1, leaf)) continue;
    // Every right leaf touches the left half's face x = 16 (the cut is along x only once).
    EXPECT_TRUE(left.adjacent(leaf)) << tree.describe(leaf);
    EXPECT_EQ(left.adjacent(leaf), tandem::boxes_share_face(tree.node(1).cells, tree.node(leaf).cells));
  }
}

// A worker that takes a task and never finishes it holds the run: the others end up waiting for
// it. The manager takes the task back after its bound by making the worker leave; its leaf is then
// handed out again and the run completes with every leaf extracted once more, by another worker.
TEST(Schedule, ATaskNeverFinishedIsHandedOutAgainOnceItsWorkerLeaves) {
  const BlockTree tree(cells(32, 32, 32), 16);
  Schedule s(tree);
  s.join(1);
  s.join(2);
  const Decision held = s.next(1);
  ASSERT_EQ(held.kind, TaskKind::extract);
  // Worker 2 does everything it can; it is left waiting for worker 1's leaf.
  std::size_t steps = 0;
  Decision d;
  for (d = s.next(2); d.kind != TaskKind::wait && steps < 100; d = s.next(2), ++steps)
    if (d.kind == TaskKind::send) {
      ASSERT_TRUE(s.arrived(2, d.transfer));
    } else if (d.kind != TaskKind::finished) {
      ASSERT_NE(d.leaf, held.leaf);
      s.done(2);
    }
  ASSERT_EQ(d.kind, TaskKind::wait) << "worker 2 should be left waiting";
  EXPECT_FALSE(s.complete());
  EXPECT_EQ(s.unprocessed(), 0u);
  // Past the bound: worker 1 leaves, its leaf (and any surface sent to it) is unprocessed again and
  // goes to worker 2.
  const std::vector<NodeId> redo = s.leave(1);
  EXPECT_NE(std::find(redo.begin(), redo.end(), held.leaf), redo.end());
  bool extracted_again = false;
  for (d = s.next(2); !s.complete() && steps < 200; d = s.next(2), ++steps) {
    if (d.kind == TaskKind::extract) extracted_again = extracted_again || d.leaf == held.leaf;
    if (d.kind == TaskKind::send) {
      ASSERT_TRUE(s.arrived(2, d.transfer));
    } else if (d.kind != TaskKind::wait) {
      s.done(2);
    }
  }
  EXPECT_TRUE(extracted_again);
  EXPECT_TRUE(s.complete());
  EXPECT_FALSE(s.knows(1)) << "a late result of worker 1 is filtered before the schedule";
}

} // namespace
} // namespace geotandem::runtime
