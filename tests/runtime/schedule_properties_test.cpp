// The manager's decisions (algorithm 6) under random event orders (joins, late joins, deaths,
// resumed runs, retirements near a walltime), checked against a simulation of what the workers
// really hold: every leaf extracted once, every surface merged into one, the run always ends.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include "geotandem/runtime/schedule.hpp"
#include "geotandem/tandem/block_tree.hpp"
#include "schedule_support.hpp"

namespace geotandem::runtime {
namespace {

using schedule_test::cells;
using tandem::BlockTree;
using tandem::NodeId;

// What a worker really holds, simulated: leaf counts per surface.
using Surface = std::map<NodeId, int>;

struct Sim {
  explicit Sim(const BlockTree& t, std::uint32_t seed) : tree(t), s(t), rng(seed) {}
  const BlockTree& tree;
  Schedule s;
  std::mt19937 rng;
  std::map<WorkerId, Surface> surface;
  std::map<WorkerId, Decision> task;    // in progress
  std::map<TransferId, Surface> parcel; // uploaded to the manager, waiting for its merge
  std::map<NodeId, int> extracted;
  WorkerId next_id = 1;
  Surface final_surface;
  bool final_seen = false;
  std::set<WorkerId> retiring;
  std::size_t awaited = 0; // successors launched for retiring workers, not yet joined
  int fallbacks = 0;       // retiring workers told FINISHED while still holding leaves
  // Issue 55: EXTRACTs of up to `batch` leaves (a subtree), and surfaces found empty after an
  // EXTRACT or MERGE with probability `empty_share`: the worker drops them and their leaves are
  // finished (in `dropped`, never sent, merged or extracted again).
  std::size_t batch = 1;
  double empty_share = 0;
  Surface dropped;
  std::uint64_t batches = 0; // EXTRACTs of more than one leaf
  // Leaves finished by an earlier run (resume). A batch may span them and the dropped ones: the
  // worker extracts only the others (`fresh`, by worker), and no worker may hold one of them then.
  std::set<NodeId> skipped;
  std::map<WorkerId, std::vector<NodeId>> fresh;
  std::uint64_t spanned = 0; // finished leaves spanned by batches

  void join() {
    s.join(next_id);
    surface[next_id];
    ++next_id;
    if (awaited > 0) --awaited;
  }
  // An idle worker near its walltime (RETIRE is its ask); `successor`: a replacement is launched.
  void retire(WorkerId w, bool successor) {
    s.retire(w);
    retiring.insert(w);
    if (successor) ++awaited;
  }
  void kill(WorkerId w) {
    s.leave(w);
    surface.erase(w);
    task.erase(w);
    retiring.erase(w);
    // The manager drops the surfaces it held for the dead worker (their leaves are re-done).
    std::erase_if(parcel, [&](const auto& p) { return !s.transfer_target(p.first); });
  }
  void step() {
    if (surface.empty()) return join(); // everyone left: a worker is started (the manager's replacement)
    std::vector<WorkerId> ids;
    for (auto& [w, _] : surface)
      ids.push_back(w);
    const WorkerId w = ids[std::uniform_int_distribution<std::size_t>(0, ids.size() - 1)(rng)];
    auto it = task.find(w);
    if (it == task.end()) {
      s.expect_joins(awaited);
      s.set_batch(rng() % 2 ? batch : 1);
      const Decision d = s.next(w);
      if (d.kind == TaskKind::finished && !d.final && retiring.count(w)) return leave_retired(w);
      if (d.kind == TaskKind::wait || (d.kind == TaskKind::finished && !d.final)) return;
      ASSERT_FALSE(d.kind == TaskKind::send && d.target == w) << "worker " << w << " sent to itself";
      ASSERT_FALSE(d.kind == TaskKind::extract && retiring.count(w)) << "retiring worker " << w << " got EXTRACT";
      ASSERT_FALSE(d.kind == TaskKind::send && retiring.count(d.target)) << "a surface sent to a retiring worker";
      if (d.final && retiring.count(w)) { // only when nobody else could take the whole surface
        for (const auto& [other, _] : surface) {
          ASSERT_TRUE(other == w || retiring.count(other)) << "retiring worker " << w << " finished the run";
        }
      }
      task[w] = d;
      if (d.kind == TaskKind::extract) {
        const std::vector<NodeId> leaves = leaves_of(d.leaf);
        ASSERT_EQ(leaves.size(), s.leaves_under(d.leaf));
        ASSERT_LE(leaves.size(), batch) << "an EXTRACT of more leaves than the batch";
        if (leaves.size() > 1) ++batches;
        std::uint32_t finished = 0;
        std::vector<NodeId>& mine = fresh[w];
        mine.clear();
        for (NodeId leaf : leaves) {
          ASSERT_FALSE(held_anywhere(leaf)) << "a batch spans a leaf a worker holds: " << tree.describe(leaf);
          if (dropped.count(leaf) || skipped.count(leaf)) {
            ++finished; // the worker skips it
            continue;
          }
          ++extracted[leaf];
          mine.push_back(leaf);
        }
        ASSERT_EQ(d.finished, finished) << "the batch's finished leaves miscounted";
        ASSERT_LT(finished, leaves.size()) << "an EXTRACT with nothing to extract";
        spanned += finished;
      }
      return;
    }
    const Decision d = it->second;
    task.erase(it);
    Surface& mine = surface[w];
    switch (d.kind) {
    case TaskKind::extract:
      for (NodeId leaf : fresh[w])
        ++mine[leaf];
      if (drop_if_empty(w, mine)) {
        s.done(w, true);
        EXPECT_EQ(s.leaves_held(w), 0u) << "an emptied worker still holds leaves";
      } else {
        s.done(w);
      }
      break;
    case TaskKind::send:
      if (s.arrived(w, d.transfer)) parcel[d.transfer] = mine;
      mine.clear();
      break;
    case TaskKind::merge: {
      ASSERT_TRUE(parcel.count(d.transfer)) << "MERGE of a surface that never arrived";
      for (auto [leaf, n] : parcel[d.transfer])
        mine[leaf] += n;
      parcel.erase(d.transfer);
      if (drop_if_empty(w, mine)) {
        s.done(w, true);
        EXPECT_EQ(s.leaves_held(w), 0u) << "an emptied worker still holds leaves";
      } else {
        s.done(w);
      }
      break;
    }
    case TaskKind::finished:
      final_surface = mine;
      final_seen = true;
      mine.clear();
      s.done(w);
      break;
    case TaskKind::wait: break;
    }
  }
  // Whether a worker's surface, a parcel or an EXTRACT in progress holds the leaf (a surface on its
  // way to a worker that died is not held: its leaves are re-done and its bytes dropped on arrival).
  bool held_anywhere(NodeId leaf) const {
    for (const auto& [w, held] : surface) {
      auto t = task.find(w);
      if (t != task.end() && t->second.kind == TaskKind::send && !s.transfer_target(t->second.transfer)) continue;
      if (held.count(leaf)) return true;
    }
    for (const auto& [t, held] : parcel)
      if (held.count(leaf)) return true;
    for (const auto& [w, d] : task)
      if (d.kind == TaskKind::extract)
        if (auto it = fresh.find(w); it != fresh.end() && std::count(it->second.begin(), it->second.end(), leaf) > 0)
          return true;
    return false;
  }
  std::vector<NodeId> leaves_of(NodeId node) const {
    std::vector<NodeId> out;
    for (NodeId leaf : tree.leaves())
      if (tree.node(leaf).cells.lo[0] >= tree.node(node).cells.lo[0] &&
          tree.node(node).cells.contains(tree.node(leaf).cells))
        out.push_back(leaf);
    return out;
  }
  // With probability empty_share the surface is empty after the task: dropped, held by nobody.
  bool drop_if_empty(WorkerId w, Surface& mine) {
    if (empty_share <= 0 || std::uniform_real_distribution<double>(0, 1)(rng) >= empty_share) return false;
    for (auto [leaf, n] : mine)
      dropped[leaf] += n;
    mine.clear();
    (void)w;
    return true;
  }
  // A retiring worker told FINISHED leaves (the manager's depart): with leaves still held only
  // when nobody could take them and no successor was on its way.
  void leave_retired(WorkerId w) {
    if (!surface[w].empty()) {
      ++fallbacks;
      EXPECT_EQ(awaited, 0u) << "retiring worker " << w << " gave up while a successor was coming";
      for (const auto& [other, _] : surface) {
        EXPECT_TRUE(other == w || retiring.count(other))
            << "retiring worker " << w << " kept its leaves though worker " << other << " could take them";
      }
    }
    kill(w);
  }
};

// `skip_one_in`: when not 0, about one leaf in that many is finished by an earlier run (resume);
// the skipped leaves leave gaps between the aggregates that the restricted adjacency never bridges.
// `retirements`: idle workers retire at random (a successor launched for three in four of them).
// Returns the hand-backs (SENDs of retiring workers) and the retiring workers that gave up holding
// leaves.
struct Retirements {
  std::uint64_t handbacks = 0;
  int fallbacks = 0;
  std::uint64_t spanned = 0; // finished leaves that batches spanned (and the workers skipped)
};
Retirements run_random(std::uint32_t seed, unsigned skip_one_in = 0, bool retirements = false, std::size_t batch = 1,
                       double empty_share = 0) {
  std::mt19937 pick(seed);
  const std::int64_t sizes[] = {16, 24, 40, 64};
  const BlockTree tree(cells(sizes[pick() % 4], sizes[pick() % 4], sizes[pick() % 4]), 8 + 8 * (pick() % 2));
  Sim sim(tree, seed);
  sim.batch = batch;
  sim.empty_share = empty_share;
  std::set<NodeId> skipped;
  if (skip_one_in)
    for (NodeId leaf : tree.leaves())
      if (pick() % skip_one_in == 0) {
        sim.s.skip(leaf);
        skipped.insert(leaf);
        sim.skipped.insert(leaf);
      }
  const int first = 1 + static_cast<int>(pick() % 4);
  for (int i = 0; i < first; ++i)
    sim.join();
  const bool faults = seed % 2 == 0;
  int steps = 0, deaths = 0, retired = 0;
  for (; !sim.s.complete() && steps < 200000; ++steps) {
    const unsigned r = pick() % 1000;
    if (r < 5 && sim.surface.size() < 6) {
      sim.join(); // a worker joins late
    } else if (sim.awaited > 0 && r < 60) {
      sim.join(); // a retiring worker's successor
    } else if (retirements && r >= 990 && retired < 12) {
      auto it = sim.surface.begin();
      std::advance(it, pick() % sim.surface.size());
      if (!sim.task.count(it->first) && !sim.retiring.count(it->first)) {
        sim.retire(it->first, pick() % 4 != 0);
        ++retired;
      }
    } else if (faults && r < 9 && sim.surface.size() > 1 && deaths < 8) {
      auto it = sim.surface.begin();
      std::advance(it, pick() % sim.surface.size());
      sim.kill(it->first); // dies (or leaves) at any moment of any task
      ++deaths;
    }
    if (sim.surface.empty() && sim.awaited == 0 && !sim.s.complete()) sim.join();
    sim.step();
    if (::testing::Test::HasFatalFailure()) return {};
  }
  EXPECT_TRUE(sim.s.complete()) << "the run did not end after " << steps << " events";
  if (!sim.s.complete() || skipped.size() == tree.leaves().size()) return {}; // nothing was left to do
  // Every leaf not skipped exactly once in the one surface left or among those dropped with an
  // empty surface (then no final pass when every surface ended empty); a skipped leaf never extracted.
  EXPECT_TRUE(sim.final_seen || sim.dropped.size() == tree.leaves().size() - skipped.size());
  if (!sim.final_seen && sim.dropped.empty()) return {};
  for (auto [leaf, n] : sim.dropped) {
    EXPECT_EQ(n, 1) << "dropped twice: " << tree.describe(leaf);
    EXPECT_EQ(sim.final_surface.count(leaf), 0u) << "dropped and in the final surface: " << tree.describe(leaf);
    sim.final_surface[leaf] += n;
  }
  EXPECT_EQ(sim.final_surface.size(), tree.leaves().size() - skipped.size());
  for (NodeId leaf : tree.leaves()) {
    if (skipped.count(leaf)) {
      EXPECT_EQ(sim.extracted[leaf], 0) << "a finished leaf was redone: " << tree.describe(leaf);
      continue;
    }
    EXPECT_EQ(sim.final_surface[leaf], 1) << tree.describe(leaf);
    if (deaths == 0 && sim.fallbacks == 0) {
      EXPECT_EQ(sim.extracted[leaf], 1) << "extracted twice without a fault: " << tree.describe(leaf);
    }
  }
  EXPECT_TRUE(sim.parcel.empty());
  if (deaths == 0 && sim.fallbacks == 0) {
    EXPECT_EQ(sim.s.counts().redone_leaves, 0u);
  }
  return {sim.s.counts().handback, sim.fallbacks, sim.spanned};
}

// 300 event orders: odd seeds without faults, even seeds with workers dying at any moment; workers
// join late in both.
TEST(Schedule, EveryLeafOnceInTheFinalSurfaceWhateverTheOrder) {
  for (std::uint32_t seed = 1; seed <= 300; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    run_random(seed);
    if (::testing::Test::HasFailure()) return;
  }
}

// Resume: leaves finished by an earlier run are skipped (a third, or half of them, at random); the
// others are extracted once and end in one surface, with and without deaths.
TEST(Schedule, ResumedRunsSkipFinishedLeavesAndStillEnd) {
  for (std::uint32_t seed = 1; seed <= 200; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    run_random(seed, 2 + seed % 2);
    if (::testing::Test::HasFailure()) return;
  }
}

// Workers near their walltime retire at any idle moment, with and without successors, deaths and
// resumes: every leaf still ends once in the one final surface, a retiring worker never extracts
// nor receives a surface, and without a death or a give-up nothing is extracted twice.
TEST(Schedule, RetiringWorkersHandBackWhatTheyHoldWhateverTheOrder) {
  Retirements all;
  for (std::uint32_t seed = 1; seed <= 300; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Retirements r = run_random(seed, seed % 3 == 0 ? 3 : 0, true);
    all.handbacks += r.handbacks;
    all.fallbacks += r.fallbacks;
    if (::testing::Test::HasFailure()) return;
  }
  // Both ways out were taken: many hand-backs, and some give-ups (no successor launched).
  EXPECT_GT(all.handbacks, 100u);
  EXPECT_GT(all.fallbacks, 0);
  RecordProperty("handbacks", static_cast<int>(all.handbacks));
  RecordProperty("fallbacks", all.fallbacks);
}

// Issue 55: small leaves in batches (a subtree per EXTRACT, at most the batch) and surfaces found
// empty after an EXTRACT or MERGE (dropped: their leaves finished, never sent, merged or redone),
// with deaths (even seeds), resumes and retirements: every leaf still ends exactly once, in the final
// surface or dropped, and without a fault nothing is extracted twice.
TEST(Schedule, BatchesAndEmptySurfacesKeepEveryLeafOnce) {
  std::uint64_t batches = 0, spanned = 0;
  for (std::uint32_t seed = 1; seed <= 300; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const std::size_t batch = std::size_t{1} << (seed % 6);
    const double empty_share = seed % 5 == 0 ? 0.0 : (seed % 5 == 1 ? 0.95 : 0.3);
    spanned += run_random(seed, seed % 4 == 0 ? 3 : 0, seed % 3 == 0, batch, empty_share).spanned;
    if (::testing::Test::HasFailure()) return;
    batches += batch > 1 ? 1 : 0;
  }
  EXPECT_GT(batches, 0u);
  EXPECT_GT(spanned, 0u); // batches spanned skipped and dropped leaves
}

// Two workers: the one that retires SENDs its surface to the other, which gets the final
// FINISHED; nothing is extracted twice. Alone, a retiring worker waits for an expected successor
// and, when none is expected, stops holding its leaves (they become unprocessed), unless it holds
// the whole surface.
TEST(Schedule, ARetiringWorkerSendsItsSurfaceToAnotherOrWaitsForItsSuccessor) {
  const BlockTree tree(cells(32, 32, 32), 16);
  Schedule s(tree);
  s.join(1);
  s.join(2);
  ASSERT_EQ(s.next(1).kind, TaskKind::extract);
  s.done(1);
  ASSERT_EQ(s.next(2).kind, TaskKind::extract);
  s.retire(1);
  EXPECT_TRUE(s.retiring(1));
  const Decision send = s.next(1);
  ASSERT_EQ(send.kind, TaskKind::send);
  EXPECT_EQ(send.target, 2u);
  EXPECT_TRUE(s.arrived(1, send.transfer));
  EXPECT_EQ(s.next(1).kind, TaskKind::finished);
  s.leave(1);
  EXPECT_EQ(s.counts().handback, 1u);
  s.done(2);
  for (int i = 0; i < 100 && !s.complete(); ++i) {
    const Decision d = s.next(2);
    if (d.kind != TaskKind::wait && !(d.kind == TaskKind::finished && !d.final)) s.done(2);
  }
  EXPECT_TRUE(s.complete());
  EXPECT_EQ(s.counts().extract, tree.leaves().size());
  EXPECT_EQ(s.counts().redone_leaves, 0u);

  Schedule alone(tree);
  alone.join(1);
  ASSERT_EQ(alone.next(1).kind, TaskKind::extract);
  alone.done(1);
  alone.retire(1);
  alone.expect_joins(1);
  EXPECT_EQ(alone.next(1).kind, TaskKind::wait);
  alone.expect_joins(0);
  EXPECT_EQ(alone.next(1).kind, TaskKind::finished);
  EXPECT_EQ(alone.leave(1).size(), 1u);
  EXPECT_EQ(alone.unprocessed(), tree.leaves().size());

  // Holding the whole surface with nobody to take it, it finishes the run itself.
  const BlockTree one(cells(16, 16, 16), 16);
  ASSERT_EQ(one.leaves().size(), 1u);
  Schedule last(one);
  last.join(1);
  ASSERT_EQ(last.next(1).kind, TaskKind::extract);
  last.done(1);
  last.retire(1);
  last.expect_joins(1);
  const Decision fin = last.next(1);
  EXPECT_EQ(fin.kind, TaskKind::finished);
  EXPECT_TRUE(fin.final);
}

} // namespace
} // namespace geotandem::runtime
