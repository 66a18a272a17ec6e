// Component step plugins through the C ABI, on a real store: the host hands over the measures,
// checks what comes back and writes the selection; broken plugins are refused with their reason,
// and recipes put component steps only where they belong.

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <sstream>

#include "geotandem/core/error.hpp"
#include "geotandem/store/local_sink.hpp"
#include "geotandem/workflow/builtin_steps.hpp"
#include "geotandem/workflow/recipe.hpp"
#include "geotandem/workflow/registry.hpp"
#include "scratch.hpp"
#include "test_paths.hpp"

using namespace geotandem;
using namespace geotandem::workflow;

namespace {

std::string plugin_file(const std::string& name) {
  return test_paths::plugins() + "/" + name + "/geotandem_" + name + ".so";
}

// A closed tetrahedron (4 triangles) or octahedron (8) with the given key.
mesh::Component body(std::uint64_t key, bool big) {
  mesh::Component c;
  c.key = key;
  if (big) {
    c.surface.points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    c.surface.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  } else {
    c.surface.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    c.surface.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  }
  c.stats.vertex_count = c.surface.points.size();
  c.stats.triangle_count = c.surface.triangles.size();
  c.stats.closed = true;
  c.stats.volume = big ? 1.3 : 0.16;
  c.stats.area = 1.0;
  return c;
}

struct Store {
  explicit Store(const std::string& dir) : store(store::ComponentStore::create(dir, volume::Geometry{{16, 16, 16}})) {
    store::LocalSink sink(store);
    for (std::uint64_t k = 1; k <= 20; ++k)
      sink.commit(body(k * 7, k % 3 == 0));
    sink.close();
  }
  store::ComponentStore store;
};

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return {};
}

} // namespace

TEST(ComponentPlugin, SelectionIsWrittenInThePluginsOrderWithTheHostsName) {
  geotandem::testing::ScratchDir dir;
  Store s(dir.file("store"));
  PluginRegistry registry;
  registry.load_library(plugin_file("bigkeys"));
  const Plugin& step = registry.get("bigkeys");
  EXPECT_EQ(step.kind(), StepKind::component);
  // The host adds `selection` (default: the step's name) to the plugin's own parameters.
  ASSERT_EQ(step.params().size(), 2u);
  EXPECT_EQ(step.params()[1].name, "selection");
  EXPECT_EQ(step.params()[1].default_value.value(), "bigkeys");
  auto values = default_values(step.params());
  values["min_triangles"] = parse_param(step.params()[0], "8");
  values["selection"] = parse_param(step.params()[1], "octahedra");
  NullProgress progress;
  CancelToken cancel;
  std::ostringstream log_text;
  Logger log(log_text, LogLevel::warning);
  StepContext context{log, progress, cancel};
  ComponentOutcome r = step.select(s.store, values, "", context);
  // Oracle: keys k*7 with k % 3 == 0 are octahedra (8 triangles); largest key first.
  std::vector<std::uint64_t> expected;
  for (std::uint64_t k = 20; k >= 1; --k)
    if (k % 3 == 0) expected.push_back(k * 7);
  EXPECT_EQ(r.before, 20u);
  EXPECT_EQ(r.after, expected.size());
  EXPECT_EQ(r.selection, "octahedra");
  EXPECT_EQ(s.store.load_selection("octahedra").keys, expected);
  // A second step from that selection sees only its members.
  values["min_triangles"] = parse_param(step.params()[0], "0");
  values["selection"] = parse_param(step.params()[1], "again");
  ComponentOutcome again = step.select(s.store, values, "octahedra", context);
  EXPECT_EQ(again.before, expected.size());
  EXPECT_EQ(s.store.load_selection("again").keys, expected);
  EXPECT_EQ(s.store.size(), 20u) << "component steps are non-destructive";
}

TEST(ComponentPlugin, ThrowingOrLyingPluginsFailWithTheirNameAndWriteNothing) {
  geotandem::testing::ScratchDir dir;
  Store s(dir.file("store"));
  PluginRegistry registry;
  registry.load_library(plugin_file("throwing"));
  registry.load_library(plugin_file("foreignkey"));
  NullProgress progress;
  CancelToken cancel;
  std::ostringstream log_text;
  Logger log(log_text, LogLevel::warning);
  StepContext context{log, progress, cancel};
  for (const char* name : {"throwing", "foreignkey"}) {
    const Plugin& step = registry.get(name);
    std::string what = error_of([&] { step.select(s.store, default_values(step.params()), "", context); });
    EXPECT_NE(what.find(name), std::string::npos) << what;
    EXPECT_NE(what.find(plugin_file(name)), std::string::npos) << what;
    EXPECT_THROW(s.store.load_selection(name), Error) << name << " left a selection behind";
  }
  std::string thrown = error_of([&] {
    registry.get("throwing").select(s.store, default_values(registry.get("throwing").params()), "", context);
  });
  EXPECT_NE(thrown.find("threw an exception"), std::string::npos) << thrown;
  EXPECT_NE(thrown.find("exploded on purpose"), std::string::npos) << thrown;
  std::string foreign = error_of([&] {
    registry.get("foreignkey").select(s.store, default_values(registry.get("foreignkey").params()), "", context);
  });
  EXPECT_NE(foreign.find("not among the components"), std::string::npos) << foreign;
  EXPECT_EQ(s.store.size(), 20u);
}

TEST(ComponentPlugin, OtherMajorVersionAndMissingEntryPointAreRefused) {
  PluginRegistry registry;
  std::string major = error_of([&] { registry.load_library(plugin_file("nextmajor")); });
  EXPECT_NE(major.find("interface version " + std::to_string(GEOTANDEM_PLUGIN_ABI_MAJOR + 1) + "."), std::string::npos)
      << major;
  EXPECT_NE(major.find(plugin_file("nextmajor")), std::string::npos) << major;
  std::string entry = error_of([&] { registry.load_library(plugin_file("compnoentry")); });
  EXPECT_NE(entry.find("no entry point 'geotandem_plugin_entry'"), std::string::npos) << entry;
  EXPECT_EQ(registry.find("nextmajor"), nullptr);
  EXPECT_EQ(registry.find("compnoentry"), nullptr);
}

class StepKinds : public ::testing::Test {
protected:
  void SetUp() override {
    register_builtin_steps(registry);
    registry.load_library(plugin_file("boxsum"));
    registry.load_library(plugin_file("bigkeys"));
  }
  std::string refusal(const std::string& steps) {
    std::string text = "version: 1\ninput:\n  synthetic: {kind: analytic, shape: [40, 40, 40]}\nsteps:\n" + steps;
    return error_of([&] { parse_recipe(text, "r.yaml", registry); });
  }
  PluginRegistry registry;
};

TEST_F(StepKinds, RecipeWithAComponentPluginValidates) {
  auto r = parse_recipe("version: 1\ninput:\n  synthetic: {kind: analytic, shape: [40, 40, 40]}\nsteps:\n"
                        "  - step: extract\n    iso: 0.5\n  - step: bigkeys\n    min_triangles: 6\n",
                        "r.yaml", registry);
  ASSERT_EQ(r.steps.size(), 2u);
  EXPECT_EQ(r.steps[1].kind, StepKind::component);
  EXPECT_EQ(r.steps[1].params.at("selection").text, "bigkeys");
  ASSERT_EQ(r.finish.size(), 1u);
  EXPECT_EQ(r.finish[0].kind, StepKind::report);
}

TEST_F(StepKinds, ComponentStepInAnAttributeSlotIsRefusedWithLineAndColumn) {
  std::string e = refusal("  - step: boxsum\n  - step: bigkeys\n  - step: extract\n    iso: 0.5\n");
  EXPECT_NE(e.find("r.yaml:6:5: step 2 (bigkeys) works on components"), std::string::npos) << e;
  std::string fed = refusal("  - step: extract\n    iso: 0.5\n  - step: bigkeys\n    input: input\n");
  EXPECT_NE(fed.find("r.yaml:7:5: step 2 (bigkeys) takes no input"), std::string::npos) << fed;
  std::string late = refusal("  - step: extract\n    iso: 0.5\n  - step: boxsum\n");
  EXPECT_NE(late.find("r.yaml:7:5: step 2 (boxsum) comes after the extract step"), std::string::npos) << late;
}

TEST_F(StepKinds, UnknownStepAndOutputStepsInTheChainAreRefusedWithLineAndColumn) {
  std::string unknown = refusal("  - step: extract\n    iso: 0.5\n  - step: bigkey\n");
  EXPECT_NE(unknown.find("r.yaml:7:11: unknown step or plugin 'bigkey'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("did you mean 'bigkeys'?"), std::string::npos) << unknown;
  std::string exporter = refusal("  - step: extract\n    iso: 0.5\n  - step: export\n    format: ply\n");
  EXPECT_NE(exporter.find("r.yaml:7:11: step 2 (export) is an export"), std::string::npos) << exporter;
}

TEST_F(StepKinds, BlockSizeBelowTheSmallestBlockFailsValidationAtItsLine) {
  std::string e = refusal("  - step: extract\n    iso: 0.5\n    block_size: 4\n");
  EXPECT_NE(e.find("r.yaml:7:17:"), std::string::npos) << e;
  EXPECT_NE(e.find("'block_size' is 4"), std::string::npos) << e;
  EXPECT_NE(e.find("at least 8"), std::string::npos) << e;
  EXPECT_NO_THROW(parse_recipe("version: 1\ninput:\n  synthetic: {kind: analytic, shape: [40, 40, 40]}\nsteps:\n"
                               "  - step: extract\n    iso: 0.5\n    block_size: 0\n",
                               "r.yaml", registry));
}

TEST_F(StepKinds, ExportOfASelectionNoStepWritesIsRefusedAtItsLine) {
  std::string text = "version: 1\ninput:\n  synthetic: {kind: analytic, shape: [40, 40, 40]}\nsteps:\n"
                     "  - step: extract\n    iso: 0.5\n  - step: bigkeys\n    selection: big\n"
                     "output:\n  exports:\n    - format: ply\n      selection: bog\n";
  std::string e = error_of([&] { parse_recipe(text, "r.yaml", registry); });
  EXPECT_NE(e.find("r.yaml:12:18: export 1 exports selection 'bog', which no component step"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'big'?"), std::string::npos) << e;
  text.replace(text.find("bog"), 3, "big");
  auto r = parse_recipe(text, "r.yaml", registry);
  ASSERT_EQ(r.finish.size(), 2u);
  EXPECT_EQ(r.finish[0].kind, StepKind::export_step);
  EXPECT_EQ(r.output.exports.at(0).selection, "big");
}

TEST_F(StepKinds, TwoExportsToOnePathAreRefused) {
  std::string text = "version: 1\ninput:\n  synthetic: {kind: analytic, shape: [40, 40, 40]}\nsteps:\n"
                     "  - step: extract\n    iso: 0.5\noutput:\n  exports:\n    - {format: ply}\n"
                     "    - {format: ply, per_component: true}\n";
  std::string e = error_of([&] { parse_recipe(text, "r.yaml", registry); });
  EXPECT_NE(e.find("r.yaml:10:7: export 2 writes bodies.ply, like an earlier export"), std::string::npos) << e;
  text.replace(text.rfind("per_component"), 0, "path: each, ");
  EXPECT_NO_THROW(parse_recipe(text, "r.yaml", registry));
}
