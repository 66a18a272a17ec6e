// workflows/slurm.yaml: its execution section is validated, the extraction still runs in this
// process, and the run says so in its log and its report.

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "e2e_support.hpp"

namespace fs = std::filesystem;
using namespace geotandem;
using namespace geotandem::testing;

TEST(WorkflowExecution, SlurmRecipeRunsInProcessAndSaysSo) {
  ScratchDir dir;
  fs::path out = dir.path() / "out";
  auto run = run_workflow(workflow_recipe("slurm.yaml"), out, {"input.synthetic.shape=[64, 64, 48]"});
  ASSERT_EQ(run.command.exit_code, 0) << run.command.err;
  EXPECT_NE(run.command.err.find("scheduler 'slurm' with 8 worker(s) is validated, but this build starts workers "
                                 "locally only: the extraction runs in this process"),
            std::string::npos)
      << run.command.err;
  EXPECT_GT(store::ComponentStore::open(out / "store").size(), 0u);
  std::ifstream in(out / "report.html");
  std::string report((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(report.find("scheduler <b>slurm</b> with 8 worker(s)"), std::string::npos);
  EXPECT_NE(report.find("the extraction ran in this process"), std::string::npos);
}

// workflows/custom_attribute.yaml runs with the example plugin found through GEOTANDEM_PLUGIN_PATH.
TEST(WorkflowExecution, CustomAttributeRecipeRunsWithTheExamplePlugin) {
  ScratchDir dir;
  fs::path out = dir.path() / "out";
  ::setenv("GEOTANDEM_PLUGIN_PATH", TEST_PLUGIN_DIR "/avg_abs_amplitude", 1);
  auto run = run_workflow(workflow_recipe("custom_attribute.yaml"), out, {"input.synthetic.shape=[64, 64, 48]"});
  ::unsetenv("GEOTANDEM_PLUGIN_PATH");
  ASSERT_EQ(run.command.exit_code, 0) << run.command.err;
  auto store = store::ComponentStore::open(out / "store");
  EXPECT_GT(store.size(), 0u);
  EXPECT_NE(store.runs().front().parameters.find("avg_abs_amplitude"), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "bodies.ply"));
}
