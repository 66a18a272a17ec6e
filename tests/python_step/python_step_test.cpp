// The `python` step through the real geotandem executable: a Python RMS equal to the built-in one
// (the attribute cube and the extraction), in this process and with two worker processes; a
// function that raises, or returns the wrong thing, stops the run with a clear message and keeps
// what was committed; a function that cannot be imported is a validation error at its line;
// `geotandem plugins` lists the step.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "e2e_support.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/volume/io.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;
using namespace geotandem;
using namespace geotandem::testing;

namespace {

std::string module_dir() {
  return test_paths::source() + "/tests/python_step";
}

// An analytic cube (bodies where the field is >= 0.5) through one attribute into the extraction,
// in leaves of 16 cells so that there are blocks for workers and the sweep commits components
// long before it ends. `attribute` is the step's YAML (a list item's keys after "- "); line 5 of
// the recipe is the step's first line.
// With `attribute_file`, the attribute cube is written too (before the extraction, in the process
// that runs the recipe).
std::string recipe_text(const std::string& attribute, int workers, bool attribute_file = false) {
  return "version: 1\n"
         "input:\n"
         "  synthetic: {kind: analytic, shape: [64, 48, 40], seed: 3}\n"
         "steps:\n"
         "  - " +
         attribute +
         "  - step: extract\n"
         "    iso: 0.45\n"
         "    block_size: 16\n" +
         std::string(attribute_file ? "output:\n  attribute: attribute.nc\n" : "") +
         "execution:\n"
         "  workers: " +
         std::to_string(workers) + "\n";
}

std::string python_step(const std::string& function, const std::string& extra = "") {
  return "step: python\n"
         "    function: " +
         function + "\n    halo: [0, 0, 4]\n    path: " + module_dir() + "\n" + extra;
}

std::string write(const ScratchDir& dir, const std::string& name, const std::string& text) {
  const std::string path = dir.file(name);
  std::ofstream(path) << text;
  return path;
}

std::vector<float> whole_cube(const fs::path& path) {
  auto volume = volume::open_volume(path.string());
  return volume->read(volume->geometry().bounds());
}

// Component key -> volume.
std::map<std::uint64_t, double> components(const fs::path& store_dir) {
  std::map<std::uint64_t, double> out;
  for (const auto& row : store::ComponentStore::open(store_dir).query())
    out[row.key] = row.stats.volume;
  return out;
}

// Each test runs the built-in rms first, in this process, in its own scratch directory (ctest
// runs the tests as separate processes at once): its store and attribute cube are the reference.
class PythonStep : public ::testing::Test {
protected:
  void SetUp() override {
    const auto recipe = write(dir_, "builtin.yaml", recipe_text("step: rms\n    window: 9\n", 1, true));
    auto run = run_workflow(recipe, dir_.path() / "builtin");
    ASSERT_EQ(run.command.exit_code, 0) << run.command.err;
  }
  fs::path reference() const { return dir_.path() / "builtin"; }

  // Runs the recipe with the Python attribute and checks that it equals the built-in one.
  void expect_equal_to_builtin(const std::string& function, int workers) {
    const auto recipe = write(dir_, "python.yaml", recipe_text(python_step(function), workers, true));
    const fs::path out = dir_.path() / "python";
    auto run = run_workflow(recipe, out);
    ASSERT_EQ(run.command.exit_code, 0) << run.command.err;
    const auto expected = whole_cube(reference() / "attribute.nc");
    const auto got = whole_cube(out / "attribute.nc");
    ASSERT_EQ(got.size(), expected.size());
    double worst = 0.0;
    for (std::size_t n = 0; n < got.size(); ++n)
      worst = std::max(worst, static_cast<double>(std::abs(got[n] - expected[n])) /
                                  std::max(1.0, static_cast<double>(std::abs(expected[n]))));
    EXPECT_LE(worst, 1e-6) << "the Python rms differs from the built-in one";

    const auto want = components(reference() / "store");
    const auto have = components(out / "store");
    ASSERT_GE(want.size(), 5u) << "the fixture should give several components";
    EXPECT_EQ(have.size(), want.size());
    for (const auto& [key, volume] : want) {
      auto it = have.find(key);
      ASSERT_NE(it, have.end()) << "component " << key << " of the built-in run is missing";
      // Workers simplify in another order than one process: volumes within 0.5 % (README).
      EXPECT_NEAR(it->second, volume, (workers > 1 ? 0.005 : 1e-9) * std::abs(volume) + 1e-9) << key;
    }
  }

  // Runs a recipe whose function fails, NAME.yaml into the directory NAME; returns the run.
  WorkflowRun run_failing(const std::string& name, const std::string& function, int workers = 1) {
    const auto recipe = write(dir_, name + ".yaml", recipe_text(python_step(function), workers));
    return run_workflow(recipe, dir_.path() / name);
  }

  ScratchDir dir_;
};

} // namespace

TEST(PythonStepCli, ListedByPluginsWithItsParameters) {
  auto all = run_geotandem("plugins");
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const auto attributes = all.out.find("attributes:"), extraction = all.out.find("extraction:");
  const auto python = all.out.find("\n  python ");
  ASSERT_NE(python, std::string::npos) << all.out;
  EXPECT_TRUE(attributes < python && python < extraction) << "python is listed as an attribute:\n" << all.out;
  auto one = run_geotandem("plugins python");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  for (const char* word : {"python (attribute", "function", "required", "halo", "default [0, 0, 0]", "path"})
    EXPECT_NE(one.out.find(word), std::string::npos) << word << " in\n" << one.out;
}

TEST(PythonStepCli, ValidationImportsTheFunction) {
  ScratchDir dir;
  // Line 6, column 15: the value of `function:` in recipe_text.
  struct Case {
    std::string function, expected;
  } cases[] = {
      {"gt_test_missing:rms", "cannot import module 'gt_test_missing'"},
      {"gt_test_attrs:nope", "module 'gt_test_attrs' has no 'nope'"},
      {"gt_test_attrs:not_callable", "which is not callable (int)"},
      {"gt_test_broken:anything", "RuntimeError: this module refuses to be imported"},
      {"no_colon_here", "not module:function"},
  };
  for (const auto& c : cases) {
    const auto recipe = write(dir, "bad.yaml", recipe_text(python_step(c.function), 1));
    auto r = run_geotandem("validate '" + recipe + "'");
    EXPECT_EQ(r.exit_code, 2) << c.function << ": " << r.err;
    EXPECT_NE(r.err.find("bad.yaml:6:15"), std::string::npos) << c.function << ": " << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.function << ": " << r.err;
  }
  // A module raising while it is imported shows Python's traceback, down to its file.
  const auto recipe = write(dir, "bad.yaml", recipe_text(python_step("gt_test_broken:anything"), 1));
  auto broken = run_geotandem("validate '" + recipe + "'");
  EXPECT_NE(broken.err.find("Traceback (most recent call last)"), std::string::npos) << broken.err;
  EXPECT_NE(broken.err.find("gt_test_broken.py\", line 3"), std::string::npos) << broken.err;
  // A bad halo is placed at its own line.
  const auto halo =
      write(dir, "halo.yaml", recipe_text("step: python\n    function: gt_test_attrs:rms\n    halo: [0, -1, 4]\n", 1));
  auto bad_halo = run_geotandem("validate '" + halo + "'");
  EXPECT_EQ(bad_halo.exit_code, 2) << bad_halo.err;
  EXPECT_NE(bad_halo.err.find("halo.yaml:7:11"), std::string::npos) << bad_halo.err;
  EXPECT_NE(bad_halo.err.find("parameter 'halo'"), std::string::npos) << bad_halo.err;
  // The module beside the recipe is found without `path` (the recipe's directory is searched).
  fs::copy_file(module_dir() + "/gt_test_attrs.py", dir.file("gt_test_attrs.py"));
  const auto beside = write(dir, "beside.yaml", recipe_text("step: python\n    function: gt_test_attrs:rms\n", 1));
  auto found = run_geotandem("validate '" + beside + "'");
  EXPECT_EQ(found.exit_code, 0) << found.err;
}

TEST_F(PythonStep, EqualsTheBuiltInRmsInThisProcess) {
  expect_equal_to_builtin("gt_test_attrs:rms", 1);
}

TEST_F(PythonStep, EqualsTheBuiltInRmsWithTwoWorkers) {
  // Returned in the shape it was given: the step crops the halo.
  expect_equal_to_builtin("gt_test_attrs:rms_whole", 2);
}

TEST_F(PythonStep, AnExceptionStopsTheRunWithItsTracebackAndKeepsWhatWasCommitted) {
  for (int workers : {1, 2}) {
    const std::string name = "failing" + std::to_string(workers);
    // The function counts its calls in each process: a worker makes about one per leaf it extracts.
    const std::string after = workers == 1 ? "40" : "10";
    ::setenv("GT_TEST_FAIL_AFTER", after.c_str(), 1);
    auto run = run_failing(name, "gt_test_attrs:fails_later", workers);
    ::unsetenv("GT_TEST_FAIL_AFTER");
    const std::string& err = run.command.err;
    EXPECT_EQ(run.command.exit_code, 5) << err; // data refused (README's exit codes), as a failing plugin
    for (const std::string& part :
         std::vector<std::string>{"block [",
                                  "(inline, crossline, sample; the halo not included): python step (function "
                                  "gt_test_attrs:fails_later) raised ValueError:\n",
                                  "Traceback (most recent call last)", "gt_test_attrs.py\", line",
                                  "ValueError: no attribute past call " + after})
      EXPECT_NE(err.find(part), std::string::npos) << workers << " worker(s): " << part << " in\n" << err;
    EXPECT_EQ(run.command.out.find("report:"), std::string::npos) << "a failed run must not report success";
    // What was committed before the failure is whole and the built-in run's.
    const auto want = components(reference() / "store");
    auto store = store::ComponentStore::open(dir_.path() / name / "store");
    const auto kept = store.query();
    if (workers == 1) {
      EXPECT_GT(kept.size(), 0u) << "nothing was committed before the failure";
    }
    EXPECT_LT(kept.size(), want.size());
    for (const auto& row : kept) {
      ASSERT_TRUE(want.count(row.key)) << "component " << row.key << " is not the built-in run's";
      EXPECT_NEAR(row.stats.volume, want.at(row.key), 0.005 * std::abs(want.at(row.key)) + 1e-9) << row.key;
      EXPECT_NO_THROW(store.read(row)) << row.key;
    }
  }
}

TEST_F(PythonStep, WrongResultsAreRefusedNamingTheFunctionAndBlock) {
  struct Case {
    std::string function, expected;
  } cases[] = {
      {"float64", "returned an array of dtype float64; it must return float32"},
      {"wrong_shape", "), given one of shape ("},
      {"not_an_array", "returned a float, not a numpy array"},
      {"nan_here", "returned NaN at sample ("},
  };
  for (const auto& c : cases) {
    auto run = run_failing(c.function, "gt_test_attrs:" + c.function);
    EXPECT_EQ(run.command.exit_code, 5) << c.function << ": " << run.command.err;
    EXPECT_NE(run.command.err.find("python step (function gt_test_attrs:" + c.function + ")"), std::string::npos)
        << run.command.err;
    EXPECT_NE(run.command.err.find(c.expected), std::string::npos) << c.function << ": " << run.command.err;
    EXPECT_NE(run.command.err.find("geotandem: error: block ["), std::string::npos) << run.command.err;
    EXPECT_EQ(run.command.out.find("report:"), std::string::npos) << "a failed run must not report success";
  }
}

// The example recipe (workflows/python_attribute.yaml, the quickstart with its envelope in numpy)
// runs in several blocks: its function gives every sample the same bits in every block, or the
// extraction could not stitch the blocks; and the envelope is the built-in one's within rounding.
TEST(PythonStepExample, TheExampleRecipeRunsInBlocksAndMatchesTheBuiltInEnvelope) {
  ScratchDir dir;
  const std::vector<std::string> small = {"input.synthetic.shape=[96,96,64]", "steps.extract.block_size=32",
                                          "execution.workers=1", "output.attribute=attribute.nc"};
  auto python = run_workflow(workflow_recipe("python_attribute.yaml"), dir.path() / "python", small);
  ASSERT_EQ(python.command.exit_code, 0) << python.command.err;
  auto builtin = run_workflow(workflow_recipe("quickstart.yaml"), dir.path() / "builtin", small);
  ASSERT_EQ(builtin.command.exit_code, 0) << builtin.command.err;
  // The attribute written is the extraction's input, chaos x normalised envelope: the two recipes
  // differ only in how the envelope's taps are summed.
  const auto want = whole_cube(dir.path() / "builtin" / "attribute.nc");
  const auto got = whole_cube(dir.path() / "python" / "attribute.nc");
  ASSERT_EQ(got.size(), want.size());
  double worst = 0.0;
  for (std::size_t n = 0; n < got.size(); ++n)
    worst = std::max(worst, static_cast<double>(std::abs(got[n] - want[n])));
  EXPECT_LE(worst, 1e-4) << "the example's envelope differs from the built-in one";
}
