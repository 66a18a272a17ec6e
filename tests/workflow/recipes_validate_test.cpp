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

namespace fs = std::filesystem;
using geotandem::testing::run_geotandem;

namespace {

std::vector<fs::path> recipes() {
  std::vector<fs::path> found;
  for (const auto& entry : fs::directory_iterator(GEOTANDEM_WORKFLOWS_DIR))
    if (entry.path().extension() == ".yaml" || entry.path().extension() == ".yml") found.push_back(entry.path());
  std::sort(found.begin(), found.end());
  return found;
}

// Only the example plugin's directory, so that a stray plugin elsewhere cannot make a recipe pass.
class PluginPath {
public:
  PluginPath() { ::setenv("GEOTANDEM_PLUGIN_PATH", TEST_PLUGIN_DIR "/avg_abs_amplitude", 1); }
  ~PluginPath() { ::unsetenv("GEOTANDEM_PLUGIN_PATH"); }
};

} // namespace

TEST(WorkflowRecipes, TheDocumentedRecipesAreAllThere) {
  std::set<std::string> names;
  for (const auto& r : recipes())
    names.insert(r.filename().string());
  for (const char* expected : {"quickstart.yaml", "segy_chaos.yaml", "slurm.yaml", "custom_attribute.yaml"})
    EXPECT_TRUE(names.count(expected)) << expected << " is missing from " << GEOTANDEM_WORKFLOWS_DIR;
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
  auto r = run_geotandem("validate '" + std::string(GEOTANDEM_WORKFLOWS_DIR) +
                         "/segy_chaos.yaml' --set input.file=/data/survey.sgy");
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(WorkflowRecipes, SlurmRecipeKeepsItsExecutionSection) {
  auto r = run_geotandem("validate '" + std::string(GEOTANDEM_WORKFLOWS_DIR) + "/slurm.yaml'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("scheduler slurm with 8 worker(s)"), std::string::npos) << r.out;
  // A wrong resource is an error with the recipe's line and column.
  auto bad = run_geotandem("validate '" + std::string(GEOTANDEM_WORKFLOWS_DIR) +
                           "/slurm.yaml' --set execution.resources.memory=lots");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("memory 'lots'"), std::string::npos) << bad.err;
}

TEST(WorkflowRecipes, CustomAttributeRecipeNeedsItsPlugin) {
  ::unsetenv("GEOTANDEM_PLUGIN_PATH");
  auto r = run_geotandem("validate '" + std::string(GEOTANDEM_WORKFLOWS_DIR) + "/custom_attribute.yaml'");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("avg_abs_amplitude"), std::string::npos) << r.err;
}
