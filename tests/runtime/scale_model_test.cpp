// The scale model (issue 55, part 4) against this machine: a real run with 1 worker and one with 2
// are recorded (their task logs); the model, calibrated on the 1-worker run's log, predicts both
// wall times within 15 %, and calibrated on the 2-worker log predicts the 1-worker run within
// 15 % too. ctest -L scale_model. The machine is shared: a run slowed by others' load shows as a
// miss, and the figures are printed for that reason.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "geotandem/runtime/scale_model.hpp"
#include "scratch.hpp"

namespace geotandem::testing {
namespace {

double recorded_wall(const std::string& store) {
  const auto runs = runtime::read_task_log(store + "/task-log.tsv");
  EXPECT_EQ(runs.size(), 1u);
  return runs.empty() ? 0.0 : runs.back().wall_seconds;
}

TEST(ScaleModel, PredictsTheOneAndTwoWorkerRunsWithin15Percent) {
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
  for (const std::string from : {"w1", "w2"}) {
    const auto runs = runtime::read_task_log(dir.file(from) + "/task-log.tsv");
    const runtime::ScaleModelCalibration c = runtime::calibrate(runs.back());
    const tandem::BlockTree tree(runs.back().cube, runs.back().leaf_size);
    const double p1 = runtime::predict(c, tree, 1).wall, p2 = runtime::predict(c, tree, 2).wall;
    std::printf("from the %s log: 1 worker %.2f s predicted, %.2f s measured (%+.1f %%); 2 workers %.2f s predicted, "
                "%.2f s measured (%+.1f %%)\n",
                from.c_str(), p1, one, 100 * (p1 / one - 1), p2, two, 100 * (p2 / two - 1));
    EXPECT_NEAR(p1, one, 0.15 * one) << "from " << from;
    EXPECT_NEAR(p2, two, 0.15 * two) << "from " << from;
  }
}

} // namespace
} // namespace geotandem::testing
