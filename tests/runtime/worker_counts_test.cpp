// Many workers (issue 55, part 3): the same cube extracted with 1, 2, 8, 32 and 64 local workers
// (64 processes on this 2-core machine: oversubscribed) gives the components of the in-process
// run, key for key, volumes within 0.5 %. Each run's task log holds every leaf's EXTRACT.
// ctest -L workers_scale.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>

#include "geotandem/runtime/aggregate.hpp"
#include "geotandem/runtime/task_log.hpp"
#include "geotandem/tandem/block_tree.hpp"
#include "process_fixtures.hpp"
#include "scratch.hpp"

namespace geotandem::testing {
namespace {

TEST(WorkerCounts, OneToSixtyFourWorkersGiveTheSameComponentKeys) {
  ScratchDir dir;
  const std::string cube = dir.file("cube.raw");
  auto r = run_geotandem("-q synth --kind analytic --shape 49 49 49 --seed 5 --out '" + cube + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_geotandem("-q extract '" + cube + "' --iso 0.5 --block-size 8 --workers 0 --out '" + dir.file("ref") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto reference = components_of(dir.file("ref"), false);
  ASSERT_GT(reference.size(), 5u);
  const tandem::BlockTree tree(volume::Box{{0, 0, 0}, {48, 48, 48}}, 8); // 512 leaves of 6 cells
  for (const int workers : {1, 2, 8, 32, 64}) {
    SCOPED_TRACE(std::to_string(workers) + " workers");
    const std::string out = dir.file("w" + std::to_string(workers));
    r = run_geotandem("-q extract '" + cube + "' --iso 0.5 --block-size 8 --workers " + std::to_string(workers) +
                      " --out '" + out + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto got = components_of(out, workers >= 32); // the meshes read back too where it is busiest
    ASSERT_EQ(got.size(), reference.size());
    for (const auto& [key, c] : reference) {
      ASSERT_TRUE(got.count(key)) << "component " << key << " missing";
      EXPECT_NEAR(got.at(key).volume, c.volume, 0.005 * std::abs(c.volume) + 1e-9) << "component " << key;
      if (workers >= 32 && !c.cut) {
        EXPECT_TRUE(got.at(key).manifold) << "component " << key;
      }
    }
    // The task log: every leaf extracted once (an EXTRACT of a batch names its subtree's node, issue
    // 55, and counts the leaves it extracted: a batch may span leaves finished before, which its
    // worker skips), and every worker seen.
    const auto runs = runtime::read_task_log(out + "/task-log.tsv");
    ASSERT_EQ(runs.size(), 1u);
    std::set<std::int64_t> leaves;
    std::uint64_t extracted = 0;
    std::set<std::string> seen;
    for (const runtime::TaskRecord& t : runs[0].tasks) {
      if (t.kind == "EXTRACT") {
        ASSERT_GE(t.leaf, 0);
        const tandem::NodeId node = static_cast<tandem::NodeId>(t.leaf);
        std::uint64_t under = 0;
        for (tandem::NodeId n = node, end = runtime::subtree_end(tree, node); n < end; ++n)
          if (tree.node(n).is_leaf()) {
            leaves.insert(n);
            ++under;
          }
        EXPECT_GE(t.leaves, 1u) << "EXTRACT of node " << t.leaf;
        EXPECT_LE(t.leaves, under) << "EXTRACT of node " << t.leaf;
        extracted += t.leaves;
      }
      seen.insert(t.worker);
      EXPECT_LE(t.start, t.end);
    }
    EXPECT_EQ(leaves.size(), tree.leaves().size());
    EXPECT_EQ(extracted, tree.leaves().size()) << "a leaf extracted twice";
    EXPECT_EQ(runs[0].workers, static_cast<std::uint64_t>(workers));
    EXPECT_GT(runs[0].manager_cpu_seconds, 0.0);
    std::printf("%d workers: %zu tasks by %zu workers, %.2f s, manager CPU %.2f s, %llu messages\n", workers,
                runs[0].tasks.size(), seen.size(), runs[0].wall_seconds, runs[0].manager_cpu_seconds,
                static_cast<unsigned long long>(runs[0].messages_in + runs[0].messages_out));
  }
}

} // namespace
} // namespace geotandem::testing
