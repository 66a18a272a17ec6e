// A plugin that fails halfway through the extraction: the run stops with the plugin's message and
// a non-zero exit code, and the store keeps every component committed before the failure.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>

#include "e2e_support.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;
using namespace geotandem;
using namespace geotandem::testing;

namespace {

// The test plugins compute factor x (sum of the 3x3x3 neighbourhood): with factor 1/27 the local
// mean of the analytic field (bodies are {value >= 0.5}; iso 0.4 keeps some of the tiny bubbles). "failing" refuses
// every box from the middle inline on. Marching cubes reads a block's samples in slabs (a leaf of up to 128 cells
// in one read), so the recipe asks for leaves of 16 cells: the blocks of the first half are extracted, and their
// finished components committed, before a block starting past the middle is read and refused.
std::string recipe(const std::string& plugin, bool in_process) {
  return "version: 1\n"
         "input:\n"
         "  synthetic: {kind: analytic, shape: [96, 64, 48], seed: 3}\n"
         "steps:\n"
         "  - step: " +
         plugin +
         "\n"
         "    factor: 0.037037037\n"
         "  - step: extract\n"
         "    iso: 0.4\n"
         "    block_size: 16\n"
         "  - step: remove_bubbles\n"
         "    min_volume_fraction: 0.01\n" +
         // In this process, the sweep's order makes "every component ending before the failing
         // inline is committed" hold. Workers (the default: one per core) take blocks in the
         // schedule's order and may reach the failing half first.
         std::string(in_process ? "execution:\n  workers: 1\n" : "");
}

std::string write_recipe(const ScratchDir& dir, const std::string& plugin, bool in_process = true) {
  std::string path = dir.file(plugin + (in_process ? "" : "-workers") + ".yaml");
  std::ofstream(path) << recipe(plugin, in_process);
  return path;
}

class PluginPath {
public:
  PluginPath() {
    ::setenv("GEOTANDEM_PLUGIN_PATH", (test_paths::plugins() + "/failing:" + test_paths::plugins() + "/boxsum").c_str(),
             1);
  }
  ~PluginPath() { ::unsetenv("GEOTANDEM_PLUGIN_PATH"); }
};

} // namespace

TEST(WorkflowFailure, PluginErrorStopsTheRunAndKeepsCommittedComponents) {
  ScratchDir dir;
  PluginPath plugins;
  // The same chain with the plugin that does not fail: what the first half should hold.
  auto reference = run_workflow(write_recipe(dir, "boxsum"), dir.path() / "reference");
  ASSERT_EQ(reference.command.exit_code, 0) << reference.command.err;
  auto failed = run_workflow(write_recipe(dir, "failing"), dir.path() / "failed");

  EXPECT_NE(failed.command.exit_code, 0);
  EXPECT_NE(failed.command.err.find("refusing box starting at inline "), std::string::npos) << failed.command.err;
  EXPECT_NE(failed.command.err.find("failing"), std::string::npos) << failed.command.err;
  // The attributes are computed as the extraction reads them: the error names that step, at its
  // line in the recipe (line 7, column 5, the step's first key).
  EXPECT_NE(failed.command.err.find("in the recipe's step 'extract' at "), std::string::npos) << failed.command.err;
  EXPECT_NE(failed.command.err.find(".yaml:7:5"), std::string::npos) << failed.command.err;
  EXPECT_EQ(failed.command.out.find("report:"), std::string::npos) << "a failed run must not report success";

  auto store = store::ComponentStore::open(dir.path() / "failed" / "store");
  auto kept = store.query();
  ASSERT_GT(kept.size(), 0u) << "nothing was committed before the failure";
  auto state = read_json(dir.path() / "failed" / "state.json");
  EXPECT_FALSE(state.at("extract").at("done").get<bool>()) << state.dump(2);

  // Every component the failed run committed is one of the reference run's, whole: same key (keys
  // do not depend on the run), same triangles and volume, and its record reads back.
  auto reference_store = store::ComponentStore::open(dir.path() / "reference" / "store");
  for (const auto& row : kept) {
    auto twin = reference_store.find(row.key);
    ASSERT_TRUE(twin.has_value()) << "component " << row.key << " is not in the reference run";
    EXPECT_EQ(row.stats.triangle_count, twin->stats.triangle_count) << row.key;
    EXPECT_NEAR(row.stats.volume, twin->stats.volume, 1e-9 * std::max(1.0, std::abs(twin->stats.volume))) << row.key;
    EXPECT_NO_THROW(store.read(row)) << row.key;
  }
  // Nothing lost: every reference component that ends well before the failing inline is there.
  // The extraction hands a finished component to the store only once the sweep is past its time
  // lag (reach = height + radius of its last edges, a few layers), so components ending in the
  // last layers before the failure were never committed; 10 layers is a safe margin.
  auto truth = read_json(dir.path() / "reference" / "truth.json");
  std::size_t expected = 0;
  for (const auto& row : reference_store.query()) {
    double hi_i = -1e300;
    for (const auto& point : reference_store.read(row).points)
      hi_i = std::max(hi_i, to_index(truth, point)[0]);
    if (hi_i > 48 - 10) continue;
    ++expected;
    EXPECT_TRUE(store.contains(row.key)) << "component " << row.key << " (ends at inline index " << hi_i
                                         << ") was lost";
  }
  EXPECT_GE(expected, 5u) << "the fixture should put many components in the first half";
  EXPECT_LT(store.size(), reference_store.size());
}

// The same failure in a worker: the run stops with the plugin's message, naming the worker, and
// whatever the workers committed before it is whole and equal to the reference run's.
TEST(WorkflowFailure, PluginErrorInAWorkerKeepsWhatWasCommittedWhole) {
  ScratchDir dir;
  PluginPath plugins;
  auto reference = run_workflow(write_recipe(dir, "boxsum"), dir.path() / "reference");
  ASSERT_EQ(reference.command.exit_code, 0) << reference.command.err;
  auto failed = run_workflow(write_recipe(dir, "failing", false), dir.path() / "failed");
  EXPECT_NE(failed.command.exit_code, 0);
  EXPECT_NE(failed.command.exit_code, 70) << failed.command.err;
  EXPECT_NE(failed.command.err.find("refusing box starting at inline "), std::string::npos) << failed.command.err;
  EXPECT_NE(failed.command.err.find("worker"), std::string::npos) << failed.command.err;
  EXPECT_NE(failed.command.err.find("in the recipe's step 'extract' at "), std::string::npos) << failed.command.err;
  EXPECT_EQ(failed.command.out.find("report:"), std::string::npos) << "a failed run must not report success";
  auto store = store::ComponentStore::open(dir.path() / "failed" / "store");
  auto reference_store = store::ComponentStore::open(dir.path() / "reference" / "store");
  for (const auto& row : store.query()) {
    auto twin = reference_store.find(row.key);
    ASSERT_TRUE(twin.has_value()) << "component " << row.key << " is not in the reference run";
    // Workers simplify in another order than one process: same keys, volumes within 0.5 %.
    EXPECT_NEAR(row.stats.volume, twin->stats.volume, 0.005 * std::abs(twin->stats.volume) + 1e-9) << row.key;
    EXPECT_NO_THROW(store.read(row)) << row.key;
  }
  EXPECT_LT(store.size(), reference_store.size());
}
