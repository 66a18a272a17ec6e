// workflows/slurm.yaml: its workers are Slurm jobs. Where no Slurm is reachable the run stops with
// a clear error naming the backend and the command (the real Slurm runs are in tests/schedulers);
// with --scheduler local the same recipe runs with local worker processes and the report says so.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <thread>

#include "e2e_support.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;
using namespace geotandem;
using namespace geotandem::testing;

TEST(WorkflowExecution, SlurmRecipeWithoutSlurmIsAClearError) {
  ScratchDir dir;
  fs::path out = dir.path() / "out";
  const char* old_path = std::getenv("PATH");
  const std::string saved = old_path ? old_path : "";
  fs::create_directories(dir.path() / "no-bin");
  ::setenv("PATH", (dir.path() / "no-bin").c_str(), 1); // no sbatch here
  auto run = run_workflow(workflow_recipe("slurm.yaml"), out, {"input.synthetic.shape=[64, 64, 48]"});
  ::setenv("PATH", saved.c_str(), 1);
  EXPECT_NE(run.command.exit_code, 0);
  EXPECT_NE(run.command.exit_code, 70);
  EXPECT_NE(run.command.err.find("slurm: `sbatch"), std::string::npos) << run.command.err;
  EXPECT_NE(run.command.err.find("-p normal"), std::string::npos) << run.command.err;
}

TEST(WorkflowExecution, SlurmRecipeRunsWithLocalWorkersAndSaysSo) {
  ScratchDir dir;
  fs::path out = dir.path() / "out";
  auto run = run_workflow(workflow_recipe("slurm.yaml"), out,
                          {"input.synthetic.shape=[64, 64, 48]", "execution.workers=2", "execution.scheduler=local"});
  ASSERT_EQ(run.command.exit_code, 0) << run.command.err;
  EXPECT_GT(store::ComponentStore::open(out / "store").size(), 0u);
  const std::string report = read_text(out / "report.html");
  EXPECT_NE(report.find("2 local worker processes"), std::string::npos);
}

// workflows/custom_attribute.yaml runs with the example plugin found through GEOTANDEM_PLUGIN_PATH.
TEST(WorkflowExecution, CustomAttributeRecipeRunsWithTheExamplePlugin) {
  ScratchDir dir;
  fs::path out = dir.path() / "out";
  ::setenv("GEOTANDEM_PLUGIN_PATH", (test_paths::plugins() + "/avg_abs_amplitude").c_str(), 1);
  auto run = run_workflow(workflow_recipe("custom_attribute.yaml"), out, {"input.synthetic.shape=[64, 64, 48]"});
  ::unsetenv("GEOTANDEM_PLUGIN_PATH");
  ASSERT_EQ(run.command.exit_code, 0) << run.command.err;
  auto store = store::ComponentStore::open(out / "store");
  EXPECT_GT(store.size(), 0u);
  EXPECT_NE(store.runs().front().parameters.find("avg_abs_amplitude"), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "bodies.ply"));
}

// The quickstart says no `workers`: a cube of several blocks gets one local worker per core (at
// most one per block), and the report states the workers it really used, not the recipe's default.
TEST(WorkflowExecution, ReportStatesTheWorkersTheDefaultGave) {
  ScratchDir dir;
  fs::path out = dir.path() / "out";
  auto run = run_workflow(workflow_recipe("quickstart.yaml"), out,
                          {"input.synthetic.shape=[64, 64, 48]", "steps.extract.block_size=16"});
  ASSERT_EQ(run.command.exit_code, 0) << run.command.err;
  const std::string report = read_text(out / "report.html");
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const std::string expected = cores >= 2 ? std::to_string(std::min(cores, 48u)) + " local worker processes"
                                          : std::string("local, in this process");
  EXPECT_NE(report.find(expected), std::string::npos) << "expected '" << expected << "'";
}

// execution.relay_memory reaches the manager: with 0 every partial surface waits for its merge in
// a file beside the store, the run's statistics count them, and no file is left.
TEST(WorkflowExecution, RelayMemoryFromTheRecipeSendsWaitingSurfacesToDisk) {
  ScratchDir dir;
  fs::path out = dir.path() / "out";
  auto run = run_workflow(workflow_recipe("quickstart.yaml"), out,
                          {"input.synthetic.shape=[64, 64, 48]", "steps.extract.block_size=16", "execution.workers=2",
                           "execution.relay_memory=0"});
  ASSERT_EQ(run.command.exit_code, 0) << run.command.err;
  auto store = store::ComponentStore::open(out / "store");
  const auto statistics = nlohmann::json::parse(store.runs().front().statistics);
  ASSERT_TRUE(statistics.contains("relay")) << statistics.dump();
  EXPECT_GT(statistics["relay"]["spilled"].get<std::uint64_t>(), 0u) << statistics.dump();
  EXPECT_EQ(statistics["relay"]["spilled"], statistics["tasks"]["merge"]) << statistics.dump();
  EXPECT_FALSE(fs::exists(out / "store.relay"));
}

// Without workers nothing is relayed: a recipe's relay_memory is said to be ignored, not dropped
// silently, and the run goes on.
TEST(WorkflowExecution, RelayMemoryWithoutWorkersIsSaidToBeIgnored) {
  ScratchDir dir;
  fs::path out = dir.path() / "out";
  auto run = run_workflow(workflow_recipe("quickstart.yaml"), out,
                          {"input.synthetic.shape=[64, 64, 48]", "execution.workers=1", "execution.relay_memory=64M"});
  ASSERT_EQ(run.command.exit_code, 0) << run.command.err;
  EXPECT_NE(run.command.err.find("execution.relay_memory is ignored"), std::string::npos) << run.command.err;
  EXPECT_GT(store::ComponentStore::open(out / "store").size(), 0u);
  auto quiet = run_workflow(workflow_recipe("quickstart.yaml"), dir.path() / "quiet",
                            {"input.synthetic.shape=[64, 64, 48]", "execution.workers=1"});
  ASSERT_EQ(quiet.command.exit_code, 0) << quiet.command.err;
  EXPECT_EQ(quiet.command.err.find("relay_memory"), std::string::npos) << quiet.command.err;
}
