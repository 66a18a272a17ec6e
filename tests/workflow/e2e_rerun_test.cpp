// Reruns: a second run of the same recipe reuses the finished extraction, neither extracting again
// nor touching the components on disk; a changed component-step parameter recomputes that step and
// the ones after it; a changed extraction parameter is refused without --fresh and recomputed with
// it.

#include <gtest/gtest.h>

#include <fstream>
#include <iostream>
#include <map>

#include "e2e_support.hpp"

namespace fs = std::filesystem;
using namespace geotandem;
using namespace geotandem::testing;

namespace {

// The quickstart chain on a smaller cube: the test is about reuse, not about the bodies.
const std::vector<std::string> small = {"input.synthetic.shape=[96, 96, 64]", "input.synthetic.seed=5"};

std::vector<std::string> with(std::vector<std::string> sets, const std::string& more) {
  sets.push_back(more);
  return sets;
}

// Every file of the store's shards with its size and modification time: what a rerun that wrote
// components again would change.
std::map<std::string, std::pair<std::uintmax_t, std::int64_t>> shard_files(const fs::path& store_dir) {
  std::map<std::string, std::pair<std::uintmax_t, std::int64_t>> files;
  for (const auto& entry : fs::recursive_directory_iterator(store_dir / "shards"))
    if (entry.is_regular_file())
      files[entry.path().lexically_relative(store_dir).string()] = {entry.file_size(),
                                                                    entry.last_write_time().time_since_epoch().count()};
  return files;
}

nlohmann::json selection_parameters(const fs::path& store_dir, const std::string& name) {
  auto store = store::ComponentStore::open(store_dir);
  return nlohmann::json::parse(store.load_selection(name).parameters);
}

} // namespace

TEST(WorkflowRerun, SecondRunReusesTheExtractionAndChangedStepsAreRecomputed) {
  ScratchDir dir;
  fs::path out = dir.path() / "out";
  std::string recipe = workflow_recipe("quickstart.yaml");

  auto first = run_workflow(recipe, out, small);
  ASSERT_EQ(first.command.exit_code, 0) << first.command.err;
  EXPECT_EQ(first.command.out.find("(reused)"), std::string::npos) << first.command.out;
  auto state = read_json(out / "state.json");
  ASSERT_TRUE(state.at("extract").at("done").get<bool>()) << state.dump(2);
  std::string fingerprint = state.at("extract").at("fingerprint");
  std::uint64_t components = state.at("extract").at("components");
  auto kept_before = store::ComponentStore::open(out / "store").load_selection("kept").keys;
  auto shards_before = shard_files(out / "store");
  ASSERT_FALSE(shards_before.empty());
  EXPECT_NE(first.command.err.find("layers+merges"), std::string::npos)
      << "the extraction's progress: " << first.command.err;

  auto second = run_workflow(recipe, out, small);
  ASSERT_EQ(second.command.exit_code, 0) << second.command.err;
  EXPECT_NE(second.command.out.find("(reused)"), std::string::npos) << second.command.out;
  EXPECT_NE(second.command.err.find("reusing the finished extraction"), std::string::npos) << second.command.err;
  EXPECT_EQ(second.command.err.find("layers+merges"), std::string::npos) << "extracted again: " << second.command.err;
  EXPECT_EQ(shard_files(out / "store"), shards_before) << "the rerun rewrote components";
  // Only printed: on a busy machine both runs' times are noisy, and the rerun's is mostly the start
  // of the process (what bench/ measures is speed; this test is about what is reused).
  std::cout << "  first run " << first.cpu_seconds << " s CPU (" << first.seconds << " s wall), rerun "
            << second.cpu_seconds << " s CPU (" << second.seconds << " s wall)\n";
  state = read_json(out / "state.json");
  EXPECT_EQ(state.at("extract").at("fingerprint"), fingerprint);
  {
    auto store = store::ComponentStore::open(out / "store");
    EXPECT_EQ(store.runs().size(), 1u) << "the rerun extracted again";
    EXPECT_EQ(store.size(), components);
    EXPECT_EQ(store.load_selection("kept").keys, kept_before);
  }
  const std::string report = read_text(out / "report.html");
  EXPECT_NE(report.find("reused from a previous run"), std::string::npos);

  // A stricter bubble rule: the extraction is reused, remove_bubbles and sort_by_azimuth are
  // recomputed from it.
  auto stricter = run_workflow(recipe, out, with(small, "steps.remove_bubbles.min_volume_fraction=0.3"));
  ASSERT_EQ(stricter.command.exit_code, 0) << stricter.command.err;
  EXPECT_NE(stricter.command.out.find("(reused)"), std::string::npos) << stricter.command.out;
  auto kept = selection_parameters(out / "store", "kept");
  EXPECT_DOUBLE_EQ(kept.at("min_volume_fraction").get<double>(), 0.3);
  EXPECT_LT(kept.at("after").get<std::uint64_t>(), kept_before.size());
  auto sorted = selection_parameters(out / "store", "sorted");
  EXPECT_EQ(sorted.at("from"), "kept");
  EXPECT_EQ(sorted.at("ranking").size(), kept.at("after").get<std::size_t>());

  // Another isovalue changes the extraction: refused while the old store is there ...
  auto refused = run_workflow(recipe, out, with(small, "steps.extract.iso=0.35"));
  EXPECT_NE(refused.command.exit_code, 0);
  EXPECT_NE(refused.command.err.find("--fresh"), std::string::npos) << refused.command.err;
  // ... and recomputed, with everything after it, with --fresh.
  auto fresh = run_workflow(recipe, out, with(small, "steps.extract.iso=0.35"), "--fresh");
  ASSERT_EQ(fresh.command.exit_code, 0) << fresh.command.err;
  EXPECT_EQ(fresh.command.out.find("(reused)"), std::string::npos) << fresh.command.out;
  state = read_json(out / "state.json");
  EXPECT_NE(state.at("extract").at("fingerprint"), fingerprint);
  auto store = store::ComponentStore::open(out / "store");
  EXPECT_EQ(store.runs().size(), 1u);
  EXPECT_NE(store.size(), components);
  EXPECT_NEAR(nlohmann::json::parse(store.runs().front().parameters).at("iso").get<double>(), 0.35, 1e-6); // a float
}

TEST(WorkflowRerun, AComponentStepThatKeepsNothingStillWritesTheReportAndNoStaleExport) {
  ScratchDir dir;
  fs::path out = dir.path() / "out";
  std::string recipe = workflow_recipe("quickstart.yaml");
  auto first = run_workflow(recipe, out, small);
  ASSERT_EQ(first.command.exit_code, 0) << first.command.err;
  ASSERT_TRUE(fs::exists(out / "bodies.ply"));

  // A bubble rule no body passes: the exports have nothing to write. The run used to stop there
  // ("no component to export", exit 2) before the report, leaving the first run's exports and
  // report in place as if they were this run's.
  auto none = run_workflow(recipe, out, with(small, "steps.remove_bubbles.min_volume=1e30"));
  ASSERT_EQ(none.command.exit_code, 0) << none.command.err;
  EXPECT_NE(none.command.out.find(", 0 kept"), std::string::npos) << none.command.out;
  for (const char* file : {"bodies.ply", "bodies.vtp", "bodies.ts"}) {
    EXPECT_FALSE(fs::exists(out / file)) << file << " of the first run is still there";
    EXPECT_NE(none.command.err.find(std::string("no ") + file + " written"), std::string::npos) << none.command.err;
  }
  const std::string report = read_text(out / "report.html");
  EXPECT_NE(report.find("<span class=\"kept\">0 kept</span>"), std::string::npos) << "the report is the first run's";
  EXPECT_NE(report.find("nothing to export"), std::string::npos);

  // An export the recipe writes outside its output directory is never removed.
  const fs::path outside = dir.path() / "mine.ply";
  { std::ofstream(outside) << "not geotandem's"; }
  auto kept_outside =
      run_workflow(recipe, out,
                   with(with(small, "steps.remove_bubbles.min_volume=1e30"),
                        "output.exports=[{format: ply, path: " + fs::relative(outside, out).string() + "}]"));
  ASSERT_EQ(kept_outside.command.exit_code, 0) << kept_outside.command.err;
  EXPECT_TRUE(fs::exists(outside));
  EXPECT_NE(kept_outside.command.err.find("already there is not this run's"), std::string::npos)
      << kept_outside.command.err;
}
