// Ctrl-C in the report phase of run-workflow (issue 52, item 6): the report was written anyway and
// the run exited 0 when it finished within the watchdog's grace. Now an interrupt at that point stops
// the run with exit 130, writes no report, and keeps what was committed: the extraction, which a
// rerun reuses.
//
// The report phase of a small run lasts milliseconds, so the run is held there with the test-only
// GEOTANDEM_TEST_HOLD_IN_REPORT (framework/workflow/src/runner.cpp): it creates the file it names,
// then waits until the run is interrupted and carries on, as a report still being written does.

#include <gtest/gtest.h>
#include <signal.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "scratch.hpp"

namespace geotandem {
namespace {

namespace fs = std::filesystem;
using testing::run_child;
using testing::ScratchDir;

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(InterruptCli, CtrlCDuringTheReportStopsTheRunWith130AndKeepsTheExtraction) {
  ScratchDir dir;
  const std::string recipe = dir.file("r.yaml"), out = dir.file("o"), marker = dir.file("in-report");
  std::ofstream(recipe) << "version: 1\ninput:\n  synthetic: {kind: analytic, shape: [40, 40, 40]}\nsteps:\n"
                           "  - step: extract\n    iso: 0.5\n  - step: remove_bubbles\n    min_volume: 1\n"
                           "output:\n  directory: "
                        << out << "\n";
  ::setenv("GEOTANDEM_TEST_HOLD_IN_REPORT", marker.c_str(), 1);
  testing::Child child(dir.path().string(), {"run-workflow", recipe});
  ::unsetenv("GEOTANDEM_TEST_HOLD_IN_REPORT"); // the child has its copy of the environment
  for (int n = 0; n < 1200 && !fs::exists(marker); ++n)
    ASSERT_FALSE(child.wait_for(0.05)) << "ended before its report phase: " << child.err();
  ASSERT_TRUE(fs::exists(marker)) << "never reached the report phase";
  child.signal(SIGINT);
  const auto code = child.wait_for(30);
  ASSERT_TRUE(code) << "the interrupt did not end the run";
  EXPECT_EQ(*code, 130) << child.out() << child.err();
  EXPECT_EQ(child.out().find("report:"), std::string::npos) << "no summary of a finished run: " << child.out();
  EXPECT_FALSE(fs::exists(out + "/report.html")) << "no report from an interrupted report phase";

  // What was committed stays: the extraction is recorded as done, and a rerun reuses it.
  const auto state = read_json(out + "/state.json");
  EXPECT_TRUE(state["extract"].value("done", false)) << state.dump();
  EXPECT_FALSE(state.contains("report")) << state.dump();
  const std::uint64_t components = state["extract"].value("components", std::uint64_t{0});
  EXPECT_GT(components, 0u) << state.dump();
  auto rerun = run_child(dir.path().string(), {"run-workflow", recipe}, 300);
  ASSERT_FALSE(rerun.hung);
  EXPECT_EQ(rerun.exit_code, 0) << rerun.err;
  EXPECT_NE(rerun.out.find("components: " + std::to_string(components) + " extracted (reused)"), std::string::npos)
      << rerun.out;
  EXPECT_TRUE(fs::exists(out + "/report.html"));
}

} // namespace
} // namespace geotandem
