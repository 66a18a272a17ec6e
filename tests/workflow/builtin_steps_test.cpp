// Each built-in step through the registry, on a real store extracted from a synthetic cube: the
// registry's steps do what the library's functions do, and the example component step keeps
// exactly the bodies its ranges describe.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "geotandem/attributes/catalog.hpp"
#include "geotandem/builtin/register.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "geotandem/workflow/component_steps.hpp"
#include "geotandem/workflow/extract_step.hpp"
#include "geotandem/workflow/registry.hpp"
#include "geotandem/workflow/report.hpp"
#include "scratch.hpp"
#include "test_paths.hpp"

using namespace geotandem;
using namespace geotandem::workflow;
namespace fs = std::filesystem;

namespace {

ParamValues values_of(const Plugin& step, const std::map<std::string, std::string>& given) {
  ParamValues values;
  for (const auto& spec : step.params()) {
    auto it = given.find(spec.name);
    values[spec.name] = parse_param(spec, it != given.end() ? it->second : spec.default_value.value());
  }
  step.check(values);
  return values;
}

class BuiltinSteps : public ::testing::Test {
protected:
  void SetUp() override {
    builtin::register_builtins(registry);
    registry.load_library(test_paths::plugins() + "/shape_filter/geotandem_shape_filter.so");
    synth::AnalyticOptions o;
    o.shape = {40, 40, 40};
    o.seed = 4;
    cube = synth::make_analytic(o);
  }
  PluginRegistry registry;
  std::shared_ptr<const volume::Volume> cube;
  NullProgress progress;
  CancelToken cancel;
  std::ostringstream log_text;
  Logger log{log_text, LogLevel::warning};
  StepContext context{log, progress, cancel};
};

} // namespace

TEST_F(BuiltinSteps, EveryStepIsInTheOneRegistryWithItsKindAndDeclaredDefaults) {
  const std::map<std::string, StepKind> expected = {{"envelope", StepKind::attribute},
                                                    {"rms", StepKind::attribute},
                                                    {"semblance", StepKind::attribute},
                                                    {"chaos", StepKind::attribute},
                                                    {"normalise", StepKind::attribute},
                                                    {"product", StepKind::attribute},
                                                    {"extract", StepKind::extract},
                                                    {"remove_bubbles", StepKind::component},
                                                    {"sort_by_azimuth", StepKind::component},
                                                    {"export", StepKind::export_step},
                                                    {"report", StepKind::report},
                                                    {"shape_filter", StepKind::component}};
  EXPECT_EQ(registry.list().size(), expected.size());
  for (const auto& [name, kind] : expected) {
    const Plugin* step = registry.find(name);
    ASSERT_NE(step, nullptr) << name;
    EXPECT_EQ(step->kind(), kind) << name;
    for (const auto& spec : step->params())
      if (spec.default_value) {
        EXPECT_NO_THROW(parse_param(spec, *spec.default_value)) << name << "." << spec.name;
      }
  }
  // The command line and recipes share these: one statement of each default.
  const ExtractionOptions d;
  auto e = values_of(registry.get("extract"), {{"iso", "0.5"}});
  EXPECT_EQ(e.at("block_size").integer, d.block_size);
  EXPECT_DOUBLE_EQ(e.at("max_error").real, tandem::SimplifyOptions{}.max_error);
  EXPECT_DOUBLE_EQ(e.at("isotropy").real, tandem::SimplifyOptions{}.isotropy);
  EXPECT_EQ(e.at("extended_time_lag").boolean, tandem::SimplifyOptions{}.extended_time_lag);
  // Checks beyond a parameter's own range run at validation: an even window, a tiny block.
  EXPECT_THROW(values_of(registry.get("rms"), {{"window", "4"}}), InvalidArgument);
  EXPECT_THROW(values_of(registry.get("extract"), {{"iso", "0.5"}, {"block_size", "4"}}), InvalidArgument);
  // A step refuses the entry points of other kinds rather than doing nothing.
  geotandem::testing::ScratchDir dir;
  auto store = store::ComponentStore::create(dir.file("s"), cube->geometry());
  EXPECT_THROW(registry.get("rms").select(store, {}, "", context), InvalidArgument);
  EXPECT_THROW(registry.get("remove_bubbles").make_attribute(cube, {}), InvalidArgument);
}

TEST_F(BuiltinSteps, AttributesThroughTheRegistryEqualTheLibrarys) {
  for (const char* name : {"envelope", "rms", "semblance", "chaos", "normalise"}) {
    const Plugin& step = registry.get(name);
    auto via_registry = step.make_attribute(cube, values_of(step, {}));
    auto direct = attributes::make_attribute(name, {cube});
    volume::Box box{{5, 6, 7}, {21, 19, 30}};
    EXPECT_EQ(via_registry->read(box), direct->read(box)) << name;
  }
}

TEST_F(BuiltinSteps, ChainOfBuiltinStepsThroughTheRegistryMatchesTheLibraryFunctions) {
  geotandem::testing::ScratchDir dir;
  auto store = store::ComponentStore::create(dir.file("store"), cube->geometry());
  auto oracle = store::ComponentStore::create(dir.file("oracle"), cube->geometry());
  // extract
  auto extract_values = values_of(registry.get("extract"), {{"iso", "0.5"}, {"block_size", "16"}});
  ExecutionContext execution;
  execution.record = {{"test", true}};
  ExtractResult r = registry.get("extract").extract(*cube, store, extract_values, execution, context);
  ExtractResult direct =
      extract_to_store(*cube, oracle, tandem::options_from_params(extract_values), execution, log, progress, cancel);
  ASSERT_GT(r.components, 3u);
  EXPECT_EQ(r.components, direct.components);
  std::vector<std::uint64_t> keys, oracle_keys;
  for (const auto& row : store.query())
    keys.push_back(row.key);
  for (const auto& row : oracle.query())
    oracle_keys.push_back(row.key);
  EXPECT_EQ(keys, oracle_keys);

  // remove_bubbles, then sort_by_azimuth from its selection
  auto bubbles =
      registry.get("remove_bubbles")
          .select(store, values_of(registry.get("remove_bubbles"), {{"min_volume_fraction", "0.01"}}), "", context);
  BubbleRemoval rules;
  rules.min_volume_fraction = 0.01;
  rules.selection = "oracle_kept";
  auto bubbles_direct = remove_bubbles(store, rules);
  EXPECT_EQ(bubbles.selection, "kept");
  EXPECT_EQ(store.load_selection("kept").keys, bubbles_direct.kept);
  EXPECT_LT(bubbles.after, bubbles.before);
  auto sorted = registry.get("sort_by_azimuth")
                    .select(store, values_of(registry.get("sort_by_azimuth"), {{"bins", "12"}}), "kept", context);
  AzimuthSorting sorting;
  sorting.bins = 12;
  sorting.from = "kept";
  sorting.selection = "oracle_sorted";
  EXPECT_EQ(store.load_selection(sorted.selection).keys, sort_by_azimuth(store, sorting).ranking);
  EXPECT_EQ(sorted.figures.at("azimuth_bins"), 12.0);

  // the example component step: exactly the bodies in its ranges, largest first
  auto shaped = registry.get("shape_filter")
                    .select(store,
                            values_of(registry.get("shape_filter"),
                                      {{"elongation_min", "0.2"}, {"dip_max", "60"}, {"selection", "shaped"}}),
                            "kept", context);
  std::vector<std::pair<double, std::uint64_t>> expect;
  store::Query q;
  q.selection = "kept";
  for (const auto& row : store.query(q))
    if (row.stats.elongation >= 0.2 && row.stats.dip <= 60)
      expect.push_back({row.stats.closed ? row.stats.volume : row.stats.area, row.key});
  std::stable_sort(expect.begin(), expect.end(), [](auto& a, auto& b) { return a.first > b.first; });
  std::vector<std::uint64_t> expect_keys;
  for (const auto& e : expect)
    expect_keys.push_back(e.second);
  EXPECT_EQ(store.load_selection("shaped").keys, expect_keys);
  EXPECT_EQ(shaped.after, expect_keys.size());
  EXPECT_EQ(shaped.before, bubbles.after);

  // export the newest selection, then the report
  const Plugin& exporter = registry.get("export");
  auto exported =
      exporter.export_components(store, values_of(exporter, {{"format", "ply"}}), "kept", dir.path(), context);
  EXPECT_EQ(exported.path, "bodies.ply");
  EXPECT_EQ(exported.components, bubbles.after);
  EXPECT_GT(fs::file_size(dir.path() / "bodies.ply"), 100u);
  // caps: false leaves out the caps of the kept bodies cut by the cube's border, and only those.
  auto faces_in = [&](const char* name) {
    std::ifstream obj(dir.path() / name);
    std::size_t faces = 0;
    for (std::string line; std::getline(obj, line);)
      faces += line.rfind("f ", 0) == 0 ? 1 : 0;
    return faces;
  };
  exporter.export_components(store, values_of(exporter, {{"format", "obj"}, {"path", "capped.obj"}}), "kept",
                             dir.path(), context);
  exporter.export_components(store, values_of(exporter, {{"format", "obj"}, {"path", "open.obj"}, {"caps", "false"}}),
                             "kept", dir.path(), context);
  bool any_cut = false;
  store::Query kept_query;
  kept_query.selection = "kept";
  for (const auto& row : store.query(kept_query))
    any_cut = any_cut || row.stats.cut_faces != 0;
  if (any_cut)
    EXPECT_LT(faces_in("open.obj"), faces_in("capped.obj"));
  else
    EXPECT_EQ(faces_in("open.obj"), faces_in("capped.obj"));
  ReportData data;
  data.title = "through the registry";
  std::string report = registry.get("report").write_report(data, values_of(registry.get("report"), {}), dir.path());
  EXPECT_EQ(report, (dir.path() / "report.html").string());
  std::ifstream in(report);
  std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("through the registry"), std::string::npos);
}

TEST_F(BuiltinSteps, AttributeDeclarationsAreTheRegistrysAndAcceptWhatTheLibraryAccepts) {
  // One parameter model: the registry lists the attribute library's own declarations (the same
  // objects, no conversion), and a value a recipe writes is accepted by validation exactly when the
  // attribute library builds the attribute from it, on values at and around every bound.
  for (const auto& attribute : attributes::builtin_attributes()) {
    const Plugin& step = registry.get(attribute.name);
    EXPECT_EQ(&step.params(), &attribute.params) << attribute.name;
    for (const auto& spec : attribute.params) {
      std::vector<std::string> probes;
      if (spec.type == ParamType::choice) {
        probes = spec.choices;
        probes.push_back("nonsense");
      } else {
        for (const auto& edge : {spec.min_value, spec.max_value})
          if (edge)
            for (double d : {-1.0, -0.5, 0.0, 0.5, 1.0, 2.0})
              probes.push_back(spec.type == ParamType::integer ? std::to_string(static_cast<long long>(*edge + d))
                                                               : std::to_string(*edge + d));
      }
      ASSERT_FALSE(probes.empty()) << attribute.name << "." << spec.name;
      for (const auto& text : probes) {
        bool registry_accepts = true, library_accepts = true;
        try {
          step.check(values_of(step, {{spec.name, text}}));
        } catch (const InvalidArgument&) {
          registry_accepts = false;
        }
        ParamValues given;
        if (spec.type == ParamType::choice)
          given[spec.name] = text;
        else if (spec.type == ParamType::integer)
          given[spec.name] = static_cast<std::int64_t>(std::stoll(text));
        else
          given[spec.name] = std::stod(text);
        try {
          std::vector<std::shared_ptr<const volume::Volume>> inputs(static_cast<std::size_t>(attribute.inputs), cube);
          attributes::make_attribute(attribute.name, inputs, given);
        } catch (const InvalidArgument&) {
          library_accepts = false;
        }
        EXPECT_EQ(registry_accepts, library_accepts) << attribute.name << "." << spec.name << " = " << text;
      }
    }
  }
}
