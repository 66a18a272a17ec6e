// The label cube from a recipe (issue 54): `output: {labels: PATH}` writes the last selection's
// bodies after the component steps, its table names exactly that selection's keys, the report says
// it, and a rerun replaces the recipe's own label cube.

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>

#include "e2e_support.hpp"
#include "geotandem/volume/io.hpp"

namespace fs = std::filesystem;
using namespace geotandem;
using namespace geotandem::testing;

TEST(WorkflowLabels, TheLastSelectionsBodiesAreLabelledAndTheReportSaysSo) {
  ScratchDir dir;
  const fs::path out = dir.path() / "out";
  const std::vector<std::string> sets = {"input.synthetic.shape=[72, 64, 48]", "input.synthetic.seed=5",
                                         "output.labels=labels.nc"};
  auto run = run_workflow(workflow_recipe("quickstart.yaml"), out, sets);
  ASSERT_EQ(run.command.exit_code, 0) << run.command.err;
  const auto table = read_json(out / "labels.nc.bodies.json");
  auto store = store::ComponentStore::open(out / "store");
  const std::string selection = table.at("selection");
  const auto kept = store.load_selection(selection).keys;
  ASSERT_FALSE(kept.empty());
  EXPECT_EQ(table.at("side"), "above");
  std::set<std::uint64_t> labelled;
  std::map<std::uint32_t, std::uint64_t> samples;
  for (const auto& body : table.at("bodies")) {
    for (std::uint64_t key : body.at("keys").get<std::vector<std::uint64_t>>())
      labelled.insert(key);
    samples[body.at("id").get<std::uint32_t>()] = body.at("samples").get<std::uint64_t>();
  }
  EXPECT_EQ(labelled, std::set<std::uint64_t>(kept.begin(), kept.end()));
  // The cube holds those IDs on those many samples, and 0 elsewhere.
  auto cube = volume::open_volume((out / "labels.nc").string());
  const auto values = cube->read(volume::Box::of_shape(cube->geometry().shape));
  std::map<std::uint32_t, std::uint64_t> counted;
  for (float v : values)
    if (v != 0.0f) ++counted[static_cast<std::uint32_t>(v)];
  EXPECT_EQ(counted, samples);
  const std::string report = read_text(out / "report.html");
  EXPECT_NE(report.find("write labels"), std::string::npos);
  EXPECT_NE(report.find("side above"), std::string::npos);
  // A rerun replaces its own label cube (no --overwrite needed), reusing the extraction.
  auto again = run_workflow(workflow_recipe("quickstart.yaml"), out, sets);
  ASSERT_EQ(again.command.exit_code, 0) << again.command.err;
  EXPECT_EQ(read_json(out / "labels.nc.bodies.json").at("bodies"), table.at("bodies"));
}

// `side: below` in a recipe's extract step (issue 54, part 5) with `min_samples` in the bubble
// removal (part 6) and a raw label cube: the store's run and the report say the side, the kept
// selection is exactly the components of at least that many samples, and every labelled body has
// the samples the store counts for it.
TEST(WorkflowLabels, SideBelowAndMinSamplesInARecipe) {
  ScratchDir dir;
  const fs::path recipe = dir.path() / "below.yaml";
  std::ofstream(recipe) << "version: 1\n"
                           "input: {synthetic: {kind: analytic, shape: [56, 52, 48], seed: 4}}\n"
                           "steps:\n"
                           "  - {step: extract, iso: 0.3, side: below, block_size: 16}\n"
                           "  - {step: remove_bubbles, min_samples: 20, selection: kept}\n"
                           "output: {labels: labels.raw}\n"
                           "execution: {workers: 1}\n";
  const fs::path out = dir.path() / "out";
  auto run = run_workflow(recipe.string(), out);
  ASSERT_EQ(run.command.exit_code, 0) << run.command.err;
  auto store = store::ComponentStore::open(out / "store");
  const auto runs = store.runs();
  ASSERT_FALSE(runs.empty());
  const auto parameters = nlohmann::json::parse(runs.back().parameters);
  EXPECT_EQ(parameters.at("side"), "below");
  EXPECT_EQ(parameters.at("identity").at("side"), "below");
  std::set<std::uint64_t> expected;
  std::size_t dropped = 0;
  std::map<std::uint64_t, std::int64_t> samples_of;
  for (const auto& row : store.query()) {
    ASSERT_TRUE(row.samples_counted);
    samples_of[row.key] = row.stats.samples;
    if (row.stats.samples >= 20)
      expected.insert(row.key);
    else
      ++dropped;
  }
  const auto kept = store.load_selection("kept").keys;
  EXPECT_EQ(std::set<std::uint64_t>(kept.begin(), kept.end()), expected);
  EXPECT_GT(dropped, 0u) << "min_samples dropped nothing: choose a larger threshold";
  ASSERT_FALSE(expected.empty());
  const std::string report = read_text(out / "report.html");
  EXPECT_NE(report.find("side below"), std::string::npos);
  const auto table = read_json(out / "labels.raw.bodies.json");
  EXPECT_EQ(table.at("side"), "below");
  for (const auto& body : table.at("bodies"))
    for (std::uint64_t key : body.at("keys").get<std::vector<std::uint64_t>>())
      EXPECT_TRUE(expected.count(key)) << "key " << key << " is labelled but not kept";
  // Every body afterwards (`store labels --all`): the surfaces of one body (its outer surface, its
  // cavities' negative) count exactly its labelled samples.
  const fs::path all = dir.path() / "all.raw";
  const auto labels =
      run_geotandem("-q store labels '" + (out / "store").string() + "' --all --out '" + all.string() + "'");
  ASSERT_EQ(labels.exit_code, 0) << labels.err;
  const auto every = read_json(dir.path() / "all.raw.bodies.json");
  std::size_t keys = 0, with_cavities = 0;
  for (const auto& body : every.at("bodies")) {
    std::int64_t counted = 0;
    const auto body_keys = body.at("keys").get<std::vector<std::uint64_t>>();
    for (std::uint64_t key : body_keys)
      counted += samples_of.at(key);
    keys += body_keys.size();
    with_cavities += body_keys.size() > 1;
    EXPECT_EQ(body.at("samples").get<std::int64_t>(), counted) << "body " << body.at("id");
  }
  EXPECT_EQ(keys, samples_of.size()) << "every component bounds one labelled body";
  EXPECT_GT(with_cavities, 0u) << "the background below iso holds the planted bodies as cavities";
  auto cube = volume::open_volume((out / "labels.raw").string());
  EXPECT_EQ(cube->geometry(), store.geometry());
}
