// Issue 55: the few leaves a killed run finished must not change how a resumed run is cut into
// tasks. A resume of the analytic 256^3 cube (leaves of 8, 2 workers) made 1056 EXTRACTs and 559
// merges against a clean run's 592 and 350, because batches stopped at every finished leaf; now a
// batch spans them (the worker skips them), so the resumed schedule makes about the clean one's
// tasks. Counts, not times: the run is replayed through the real Schedule and the manager's batch
// policy with simulated task durations.
#include <gtest/gtest.h>

#include <queue>
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

struct Tasks {
  std::uint64_t extract = 0, merge = 0, send = 0;
  std::uint64_t extracted = 0; // leaves extracted
  std::uint64_t spanned = 0;   // finished leaves inside batches (skipped by their worker)
};

// `workers` workers, a leaf costs 1 time unit to extract, a MERGE 2, a SEND 1, a WAIT 0.5; the batch
// is the manager's (extract_batch) for a target of 64 leaves.
Tasks replay(const BlockTree& tree, const std::set<NodeId>& finished, std::size_t workers) {
  Schedule s(tree);
  for (NodeId leaf : finished)
    s.skip(leaf);
  struct Event {
    double t;
    WorkerId w;
    bool operator>(const Event& o) const { return t != o.t ? t > o.t : w > o.w; }
  };
  std::priority_queue<Event, std::vector<Event>, std::greater<>> events;
  std::map<WorkerId, Decision> task;
  for (WorkerId w = 1; w <= workers; ++w) {
    s.join(w);
    events.push({0.0, w});
  }
  Tasks out;
  for (int steps = 0; !events.empty() && steps < 1000000; ++steps) {
    const Event e = events.top();
    events.pop();
    if (auto it = task.find(e.w); it != task.end()) { // the task ends
      const Decision d = it->second;
      task.erase(it);
      if (d.kind == TaskKind::send)
        s.arrived(e.w, d.transfer);
      else
        s.done(e.w);
      if (d.kind == TaskKind::finished) break;
      events.push({e.t, e.w});
      continue;
    }
    s.set_batch(extract_batch(1.0, s.unprocessed(), s.live_workers(), 4096, 64.0));
    const Decision d = s.next(e.w);
    double lasts = 0;
    switch (d.kind) {
    case TaskKind::wait: events.push({e.t + 0.5, e.w}); continue;
    case TaskKind::finished:
      if (!d.final) {
        s.leave(e.w);
        continue;
      }
      lasts = 1;
      break;
    case TaskKind::extract: {
      ++out.extract;
      const std::size_t n = s.leaves_under(d.leaf) - d.finished;
      out.extracted += n;
      out.spanned += d.finished;
      lasts = static_cast<double>(n);
      break;
    }
    case TaskKind::merge:
      ++out.merge;
      lasts = 2;
      break;
    case TaskKind::send:
      ++out.send;
      lasts = 1;
      break;
    }
    task[e.w] = d;
    events.push({e.t + lasts, e.w});
  }
  EXPECT_TRUE(s.complete()) << "the replayed run did not end";
  EXPECT_EQ(out.extracted, tree.leaves().size() - finished.size()) << "a leaf extracted twice or never";
  return out;
}

// The leaves a killed run finished: scattered (one in 64 anywhere), or where its workers were (a
// quarter of the first eighth of the tree).
std::set<NodeId> finished_leaves(const BlockTree& tree, bool clustered, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::set<NodeId> out;
  const std::vector<NodeId>& leaves = tree.leaves();
  for (std::size_t i = 0; i < leaves.size(); ++i) {
    const bool pick = clustered ? i < leaves.size() / 8 && rng() % 4 == 0 : rng() % 64 == 0;
    if (pick) out.insert(leaves[i]);
  }
  return out;
}

TEST(ScheduleResume, AResumedRunMakesTheTasksOfACleanOne) {
  const BlockTree tree(cells(256, 256, 256), 8); // 32768 leaves, as the analytic 256^3 cube
  for (std::size_t workers : {2u, 8u}) {
    const Tasks clean = replay(tree, {}, workers);
    for (bool clustered : {false, true}) {
      SCOPED_TRACE(std::to_string(workers) + " workers, finished leaves " + (clustered ? "clustered" : "scattered"));
      const std::set<NodeId> finished = finished_leaves(tree, clustered, 55);
      ASSERT_GT(finished.size(), 400u);
      const Tasks resumed = replay(tree, finished, workers);
      // About the clean run's tasks (before: 1.8x the EXTRACTs and 1.6x the merges, measured).
      EXPECT_LE(resumed.extract, clean.extract * 11 / 10 + 2);
      EXPECT_LE(resumed.merge, clean.merge * 11 / 10 + 2);
      EXPECT_GT(resumed.spanned, 0u) << "no batch spanned a finished leaf";
      std::printf("%zu workers, %zu finished leaves (%s): EXTRACT %llu, MERGE %llu against a clean run's %llu "
                  "and %llu\n",
                  workers, finished.size(), clustered ? "clustered" : "scattered",
                  static_cast<unsigned long long>(resumed.extract), static_cast<unsigned long long>(resumed.merge),
                  static_cast<unsigned long long>(clean.extract), static_cast<unsigned long long>(clean.merge));
    }
  }
}

} // namespace
} // namespace geotandem::runtime
