// The scale model (issue 55, part 4) against this machine: a real run with 1 worker and one with 2
// are recorded (their task logs); each log, replayed through the real Schedule on the recorded
// host's cores (its other load included, scale_model.hpp), predicts both runs' wall times: printed,
// and only grossly asserted (see the test); the accuracy is bench_scale_model's figure (README).
// ctest -L scale_model. The machine is shared: a run slowed by others' load shows as a miss, and
// the figures are printed for that reason.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <thread>

#include "../../framework/runtime/src/task_log.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/runtime/scale_model.hpp"
#include "scratch.hpp"

namespace geotandem::testing {
namespace {

double recorded_wall(const std::string& store) {
  const auto runs = runtime::read_task_log(store + "/task-log.tsv");
  EXPECT_EQ(runs.size(), 1u);
  return runs.empty() ? 0.0 : runs.back().wall_seconds;
}

TEST(ScaleModel, ReplaysRecordedRunsAndPrintsItsMisses) {
  ScratchDir dir;
  const std::string cube = dir.file("cube.raw");
  auto r = run_geotandem("-q synth --kind analytic --shape 161 161 161 --seed 2 --out '" + cube + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const int workers : {1, 2}) {
    r = run_geotandem("-q extract '" + cube + "' --iso 0.5 --block-size 20 --workers " + std::to_string(workers) +
                      " --out '" + dir.file("w" + std::to_string(workers)) + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const double one = recorded_wall(dir.file("w1")), two = recorded_wall(dir.file("w2"));
  ASSERT_GT(one, 0.0);
  ASSERT_GT(two, 0.0);
  std::map<std::string, std::pair<double, double>> predicted; // from a log: 1 and 2 workers
  for (const std::string from : {"w1", "w2"}) {
    const auto runs = runtime::read_task_log(dir.file(from) + "/task-log.tsv");
    const runtime::ScaleModelCalibration c = runtime::calibrate(runs.back());
    const tandem::BlockTree tree(runs.back().cube, runs.back().leaf_size);
    EXPECT_EQ(c.cores, std::thread::hardware_concurrency()) << "the log records the host's processors";
    const double p1 = runtime::predict(c, tree, 1, c.cores).wall, p2 = runtime::predict(c, tree, 2, c.cores).wall;
    // Any log prices merges: a 1-worker run has no SEND or MERGE, but its task log records the
    // merges of each EXTRACT's surface into its worker's, and those inside its batches, which size
    // surfaces (issue 55; under a sanitizer a leaf is too slow to batch: no batch merges then).
    EXPECT_GT(c.merge_fixed + c.merge_per_byte, 0.0) << from << ": no price for a MERGE";
    bool batches = false;
    for (const runtime::TaskRecord& t : runs.back().tasks)
      batches = batches || (t.kind == "EXTRACT" && t.leaves > 1);
    if (batches || from == "w2") {
      EXPECT_GT(c.bytes_k, 0.0) << from << ": no size for a partial surface";
    }
    if (from == "w1") {
      if (batches) {
        EXPECT_GT(c.batch_merges, 0u) << "the 1-worker log records no merge inside its batches";
      }
      const runtime::ScalePrediction replay2 = runtime::predict(c, tree, 2, c.cores);
      EXPECT_GT(replay2.merge, 0u);
      EXPECT_GT(replay2.work, runtime::predict(c, tree, 1, c.cores).work) << "2 workers' merges cost nothing";
    }
    predicted[from] = {p1, p2};
    std::printf("from the %s log: 1 worker %.2f s predicted, %.2f s measured (%+.1f %%); 2 workers %.2f s predicted, "
                "%.2f s measured (%+.1f %%)\n",
                from.c_str(), p1, one, 100 * (p1 / one - 1), p2, two, 100 * (p2 / two - 1));
  }
  // The accuracy is a benchmark's figure (bench_scale_model; the README has the measurements), not
  // a timed assertion: on a 1-second run of this shared 2-core machine the 1-worker replay landed
  // at +1 % to +18 %. Asserted here is what a broken model would get wrong: a replay within half of
  // the run it replays, a 2-worker speed-up predicted from the 1-worker log, and from the 2-worker log
  // no 2-worker prediction half again slower than its 1-worker one.
  EXPECT_NEAR(predicted["w1"].first, one, 0.5 * one);
  EXPECT_LT(predicted["w1"].second, predicted["w1"].first);
  EXPECT_LT(predicted["w2"].second, predicted["w2"].first * 1.5);
  // Across worker counts it is printed, not asserted: the machine's other load, which the model
  // infers from each run, moves between two runs seconds apart on this shared machine.
}

// What a manager killed mid-run had logged more than a second before is in the file: the writer
// flushes its buffer once a second, not only at the end of the run.
TEST(TaskLog, LinesReachTheFileWithinASecondWhileTheRunGoesOn) {
  ScratchDir dir;
  const std::string path = dir.file("task-log.tsv");
  runtime::TaskRecord t{.worker = "w1", .kind = "EXTRACT", .leaf = 3, .leaves = 1, .start = 0.1, .end = 0.2};
  runtime::detail::TaskLogWriter writer(path, volume::Box{{0, 0, 0}, {16, 16, 16}}, 8, 1, 2);
  writer.add(t);
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  t.leaf = 4;
  writer.add(t);
  // Read while the writer is still open (no close, no destructor): what a SIGKILL would leave.
  const auto runs = runtime::read_task_log(path);
  ASSERT_EQ(runs.size(), 1u);
  ASSERT_EQ(runs[0].tasks.size(), 2u);
  EXPECT_EQ(runs[0].tasks[1].leaf, 4);
}

// A manager killed mid-run leaves its task log's last line cut: the resumed run's block starts on a
// line of its own (the real writer), the cut line is dropped, and both runs read; a line that does
// not read anywhere else is an error naming it.
TEST(TaskLog, AKilledRunsCutLineIsDroppedAndTheResumedRunReads) {
  ScratchDir dir;
  const std::string path = dir.file("task-log.tsv");
  const volume::Box cube{{0, 0, 0}, {16, 16, 16}};
  runtime::TaskRecord t{.worker = "w1",
                        .kind = "EXTRACT",
                        .leaf = 3,
                        .leaves = 1,
                        .start = 0.1,
                        .end = 0.2,
                        .worker_ms = 90,
                        .bytes = 0,
                        .rows = 1,
                        .empty = 3,
                        .cpu_ms = 80};
  {
    runtime::detail::TaskLogWriter first(path, cube, 8, 4096, 2);
    first.add(t);
  }
  {
    std::ofstream cut(path, std::ios::app);
    cut << "w1\tSEN"; // the manager was killed here
  }
  {
    runtime::detail::TaskLogWriter second(path, cube, 8, 1, 2);
    t.leaf = 4;
    second.add(t);
    second.close({.manager_cpu_seconds = 0.5, .wall_seconds = 2.0, .workers = 1});
  }
  const auto runs = runtime::read_task_log(path);
  ASSERT_EQ(runs.size(), 2u);
  ASSERT_EQ(runs[0].tasks.size(), 1u);
  EXPECT_EQ(runs[0].batch, 4096u);
  EXPECT_EQ(runs[0].cores, 2u);
  EXPECT_TRUE(runs[0].empties);
  EXPECT_EQ(runs[0].tasks[0].empty, 3u);
  EXPECT_DOUBLE_EQ(runs[0].tasks[0].cpu_ms, 80.0);
  ASSERT_EQ(runs[1].tasks.size(), 1u);
  EXPECT_EQ(runs[1].tasks[0].leaf, 4);
  EXPECT_EQ(runs[1].batch, 1u);
  EXPECT_DOUBLE_EQ(runs[1].wall_seconds, 2.0);
  // A damaged line followed by more tasks is not a cut: an error naming its line.
  {
    std::ofstream damaged(path, std::ios::app);
    damaged << "# cube 0 0 0 16 16 16 leaf_size 8\nworker\tkind\tleaf\tleaves\tstart\tend\tworker_ms\tbytes\trows\n"
            << "w1\tEXTRACT\tx\n"
            << "w1\tEXTRACT\t3\t1\t0.1\t0.2\t90\t0\t1\n";
  }
  try {
    runtime::read_task_log(path);
    ADD_FAILURE() << "a damaged line was read";
  } catch (const geotandem::DataError& e) {
    EXPECT_NE(std::string(e.what()).find(":11:"), std::string::npos) << e.what();
  }
}

} // namespace
} // namespace geotandem::testing
