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
