// Every recipe shipped in workflows/ passes `geotandem validate`, run as a user runs it. The
// custom attribute recipe finds its plugin through GEOTANDEM_PLUGIN_PATH (the example plugin is
// built by this directory's CMakeLists.txt).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "scratch.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;
using geotandem::testing::run_geotandem;

namespace {

std::vector<fs::path> recipes() {
  std::vector<fs::path> found;
  for (const auto& entry : fs::directory_iterator(test_paths::workflows()))
    if (entry.path().extension() == ".yaml" || entry.path().extension() == ".yml") found.push_back(entry.path());
  std::sort(found.begin(), found.end());
  return found;
}

// Only the example plugin's directory, so that a stray plugin elsewhere cannot make a recipe pass.
class PluginPath {
public:
  PluginPath() { ::setenv("GEOTANDEM_PLUGIN_PATH", (test_paths::plugins() + "/avg_abs_amplitude").c_str(), 1); }
  ~PluginPath() { ::unsetenv("GEOTANDEM_PLUGIN_PATH"); }
};

} // namespace

TEST(WorkflowRecipes, TheDocumentedRecipesAreAllThere) {
  std::set<std::string> names;
  for (const auto& r : recipes())
    names.insert(r.filename().string());
  for (const char* expected : {"quickstart.yaml", "segy_chaos.yaml", "slurm.yaml", "custom_attribute.yaml"})
    EXPECT_TRUE(names.count(expected)) << expected << " is missing from " << test_paths::workflows();
}

TEST(WorkflowRecipes, EveryRecipeValidates) {
  PluginPath plugins;
  auto all = recipes();
  ASSERT_FALSE(all.empty());
  for (const auto& recipe : all) {
    auto r = run_geotandem("validate '" + recipe.string() + "'");
    EXPECT_EQ(r.exit_code, 0) << recipe << "\nstdout: " << r.out << "\nstderr: " << r.err;
    EXPECT_NE(r.out.find(": valid"), std::string::npos) << recipe << ": " << r.out;
  }
}

TEST(WorkflowRecipes, SegyPlaceholderIsReplacedWithSet) {
  auto r =
      run_geotandem("validate '" + test_paths::workflows() + "/segy_chaos.yaml' --set input.file=/data/survey.sgy");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(WorkflowRecipes, ValidateSaysHowManyWorkersARunWouldStart) {
  // Without `workers` a local run starts one per core (it printed "1 worker(s)" and ran 2).
  const std::string quickstart = test_paths::workflows() + "/quickstart.yaml";
  auto by_default = run_geotandem("validate '" + quickstart + "'");
  ASSERT_EQ(by_default.exit_code, 0) << by_default.err;
  EXPECT_NE(by_default.out.find("scheduler local with one worker per core, at most one per block"), std::string::npos)
      << by_default.out;
  auto given = run_geotandem("validate '" + quickstart + "' --set execution.workers=3");
  ASSERT_EQ(given.exit_code, 0) << given.err;
  EXPECT_NE(given.out.find("scheduler local with 3 worker(s)"), std::string::npos) << given.out;
}

TEST(WorkflowRecipes, SlurmRecipeKeepsItsExecutionSection) {
  auto r = run_geotandem("validate '" + test_paths::workflows() + "/slurm.yaml'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("scheduler slurm with 8 worker(s)"), std::string::npos) << r.out;
  // A wrong resource is an error with the recipe's line and column.
  auto bad =
      run_geotandem("validate '" + test_paths::workflows() + "/slurm.yaml' --set execution.resources.memory=lots");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("parameter 'memory' is 'lots', not a size"), std::string::npos) << bad.err;
}

TEST(WorkflowRecipes, CustomAttributeRecipeNeedsItsPlugin) {
  ::unsetenv("GEOTANDEM_PLUGIN_PATH");
  auto r = run_geotandem("validate '" + test_paths::workflows() + "/custom_attribute.yaml'");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("avg_abs_amplitude"), std::string::npos) << r.err;
}

TEST(WorkflowRecipes, ValidateRefusesWhatExtractionWouldRefuseAndDryRunWritesNothing) {
  geotandem::testing::ScratchDir dir;
  const std::string quickstart = test_paths::workflows() + "/quickstart.yaml";
  // block_size 4 used to pass validate and fail when extraction started.
  auto small = run_geotandem("validate '" + quickstart + "' --set steps.extract.block_size=4");
  EXPECT_EQ(small.exit_code, 2) << small.err;
  EXPECT_NE(small.err.find("'block_size' is 4"), std::string::npos) << small.err;
  EXPECT_NE(small.err.find("at least 8"), std::string::npos) << small.err;
  // The same bound on the command line: one declaration.
  auto cli =
      run_geotandem("extract '" + dir.file("none.sgy") + "' --iso 1 --block-size 4 --out '" + dir.file("store") + "'");
  EXPECT_EQ(cli.exit_code, 2) << cli.err;
  EXPECT_NE(cli.err.find("--block-size"), std::string::npos) << cli.err;
  EXPECT_NE(cli.err.find("at least 8"), std::string::npos) << cli.err;
  // A dry run of a synthetic recipe leaves nothing behind (it used to write truth.json).
  const fs::path out = dir.path() / "dry";
  auto dry = run_geotandem("run-workflow '" + quickstart + "' --dry-run --set 'output.directory=" + out.string() + "'");
  EXPECT_EQ(dry.exit_code, 0) << dry.err;
  EXPECT_NE(dry.out.find("nothing computed (dry run)"), std::string::npos) << dry.out;
  EXPECT_FALSE(fs::exists(out)) << "a dry run created " << out;
  EXPECT_FALSE(fs::exists(dir.path() / "store"));
}
