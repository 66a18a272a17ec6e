// The manager's decisions cost per task what they cost at 1 k leaves at 32 k and 1 M leaves too
// (issue 55, part 2: on main the cost grew with the tree, the run with the square of the blocks).
// The real Schedule is driven as the manager drives it (ask, then done or arrived), with 2 and 64
// workers whose tasks end at once, so its own CPU is all that is measured. Growth must stay
// logarithmic: the tree's depth doubles from 1 k to 1 M leaves, the per-task CPU may at most
// grow 6-fold (a noisy shared machine, caches an order larger); on main it grew about 1000-fold.
#include <gtest/gtest.h>
#include <time.h>

#include <cstdio>
#include <deque>

#include "geotandem/runtime/schedule.hpp"
#include "schedule_support.hpp"

namespace geotandem::runtime {
namespace {

using schedule_test::cells;

double thread_cpu() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Cost {
  double seconds_per_task = 0;
  std::uint64_t tasks = 0;
};

// A whole run through the schedule with `workers` workers whose tasks end at once; the CPU of the
// decisions that are tasks (EXTRACT, SEND, MERGE, FINISHED) and of their ends (done, arrived),
// per task. A worker told WAIT asks again once another task has ended, as a real one would
// after its 20 ms, not in a spin (one waiting worker per task that ends).
Cost run(const tandem::BlockTree& tree, WorkerId workers) {
  Schedule s(tree);
  std::deque<WorkerId> asking, parked;
  for (WorkerId w = 1; w <= workers; ++w) {
    s.join(w);
    asking.push_back(w);
  }
  std::uint64_t tasks = 0;
  double spent = 0;
  while (!asking.empty() || !parked.empty()) {
    if (asking.empty()) std::swap(asking, parked);
    const WorkerId w = asking.front();
    asking.pop_front();
    const double t0 = thread_cpu();
    const Decision d = s.next(w);
    switch (d.kind) {
    case TaskKind::wait: break;
    case TaskKind::send: s.arrived(w, d.transfer); break;
    case TaskKind::finished:
      if (d.final) s.done(w);
      s.leave(w);
      break;
    default: s.done(w);
    }
    const double t1 = thread_cpu();
    if (d.kind == TaskKind::wait) {
      parked.push_back(w);
      continue;
    }
    spent += t1 - t0;
    ++tasks;
    if (!parked.empty()) { // something changed: a waiting worker asks again
      asking.push_back(parked.front());
      parked.pop_front();
    }
    if (d.kind != TaskKind::finished) asking.push_back(w);
  }
  EXPECT_TRUE(s.complete());
  EXPECT_EQ(s.counts().extract, tree.leaves().size());
  return {spent / static_cast<double>(tasks), tasks};
}

TEST(ScheduleCost, PerTaskCpuGrowsAtMostLogarithmicallyFrom1kTo1MLeaves) {
  const tandem::BlockTree small(cells(128, 64, 64), 8);     // 1024 leaves
  const tandem::BlockTree middle(cells(512, 256, 128), 8);  // 32768 leaves
  const tandem::BlockTree large(cells(1024, 1024, 512), 8); // 1048576 leaves
  ASSERT_EQ(small.leaves().size(), 1024u);
  ASSERT_EQ(middle.leaves().size(), 32768u);
  ASSERT_EQ(large.leaves().size(), 1048576u);
  for (const WorkerId workers : {WorkerId{2}, WorkerId{64}}) {
    // The small tree's figure is the best of several runs: it is short enough for noise to matter.
    Cost a = run(small, workers);
    for (int i = 0; i < 4; ++i) {
      const Cost again = run(small, workers);
      if (again.seconds_per_task < a.seconds_per_task) a = again;
    }
    const Cost b = run(middle, workers);
    const Cost c = run(large, workers);
    std::printf("%u workers: %.2f us/task at 1 k leaves (%llu tasks), %.2f at 32 k (%llu), %.2f at 1 M (%llu)\n",
                workers, 1e6 * a.seconds_per_task, static_cast<unsigned long long>(a.tasks), 1e6 * b.seconds_per_task,
                static_cast<unsigned long long>(b.tasks), 1e6 * c.seconds_per_task,
                static_cast<unsigned long long>(c.tasks));
    EXPECT_LT(b.seconds_per_task, 6 * a.seconds_per_task) << workers << " workers, 32 k leaves against 1 k";
    EXPECT_LT(c.seconds_per_task, 6 * a.seconds_per_task) << workers << " workers, 1 M leaves against 1 k";
  }
}

} // namespace
} // namespace geotandem::runtime
