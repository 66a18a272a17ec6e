// A real run's report (geotandem run-workflow on the quickstart recipe, as a child process): the
// map view and the 3-D view hold every kept body, the 3-D geometry stays within the triangle
// budget, and three.js is inlined (no network).

#include <gtest/gtest.h>

#include <algorithm>

#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "e2e_support.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/workflow/report.hpp"
#include "geotandem/workflow/report_views.hpp"

namespace geotandem {
namespace {

using testing::run_workflow;
using testing::ScratchDir;
using testing::workflow_recipe;

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
    ++n;
  return n;
}

TEST(ReportRun, MapAndThreeDViewsHoldTheKeptBodies) {
  ScratchDir dir;
  const auto out = dir.path() / "run";
  auto run = run_workflow(workflow_recipe("quickstart.yaml"), out, {"input.synthetic.shape=[96, 96, 80]"});
  ASSERT_EQ(run.command.exit_code, 0) << run.command.err;

  // What was kept: the last selection the component steps saved.
  const auto store = store::ComponentStore::open(out / "store");
  const store::Selection kept = store.load_selection("sorted");
  ASSERT_GE(kept.keys.size(), 2u) << "the quickstart keeps several bodies";
  const std::set<std::uint64_t> kept_keys(kept.keys.begin(), kept.keys.end());

  std::ifstream in(out / "report.html");
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_NE(html.find("<h2>Bodies</h2>"), std::string::npos);

  // Map view: one footprint per kept body, with the survey, north arrow and scale bar.
  EXPECT_EQ(count_of(html, "class=\"footprint\""), kept.keys.size());
  for (auto key : kept.keys)
    EXPECT_NE(html.find("class=\"footprint\" data-key=\"" + std::to_string(key) + "\""), std::string::npos) << key;
  EXPECT_EQ(count_of(html, "class=\"survey\""), 1u);
  EXPECT_EQ(count_of(html, "class=\"north-arrow\""), 1u);
  EXPECT_EQ(count_of(html, "class=\"scale-bar\""), 1u);

  // 3-D view: the canvas, three.js inlined, nothing fetched from elsewhere.
  EXPECT_NE(html.find("<canvas id=\"gt-view\""), std::string::npos);
  EXPECT_NE(html.find("three.js r111"), std::string::npos);
  EXPECT_EQ(html.find("<script src="), std::string::npos);
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);

  // The bodies' geometry: as many bodies as were kept, the same keys, within the budget, valid
  // triangles, and points inside the survey's sample range.
  const std::string open_tag = "<script type=\"application/json\" id=\"geotandem-bodies\">";
  const auto begin = html.find(open_tag);
  ASSERT_NE(begin, std::string::npos);
  const auto end = html.find("</script>", begin);
  const auto data = nlohmann::json::parse(html.substr(begin + open_tag.size(), end - begin - open_tag.size()));
  ASSERT_EQ(data["bodies"].size(), kept.keys.size());
  EXPECT_EQ(data["triangle_budget"].get<std::size_t>(), workflow::kDisplayTriangleBudget);
  std::size_t triangles = 0;
  const double z_min = data["z_min"], z_max = data["z_max"];
  for (const auto& b : data["bodies"]) {
    EXPECT_TRUE(kept_keys.count(b["key"].get<std::uint64_t>())) << b["key"];
    const auto row = store.find(b["key"].get<std::uint64_t>());
    ASSERT_TRUE(row.has_value());
    EXPECT_EQ(b["full_triangles"].get<std::uint64_t>(), row->stats.triangle_count);
    EXPECT_NEAR(b["azimuth"].get<double>(), row->stats.azimuth, 0.01);
    const auto& points = b["points"];
    const auto& tris = b["triangles"];
    ASSERT_EQ(points.size() % 3, 0u);
    ASSERT_EQ(tris.size() % 3, 0u);
    EXPECT_GT(tris.size(), 0u) << "every kept body is drawn";
    triangles += tris.size() / 3;
    for (const auto& v : tris)
      ASSERT_LT(v.get<std::size_t>(), points.size() / 3);
    for (std::size_t n = 2; n < points.size(); n += 3) {
      ASSERT_GE(points[n].get<double>(), z_min - 1e-6);
      ASSERT_LE(points[n].get<double>(), z_max + 1e-6);
    }
  }
  EXPECT_LE(triangles, workflow::kDisplayTriangleBudget);

  // The same store through a small budget: decimated, still every body, within that budget.
  std::vector<workflow::ReportComponent> components;
  for (const auto& row : store.query())
    components.push_back({row.key, row.stats.volume, row.stats.azimuth, row.stats.elongation, row.stats.triangle_count,
                          row.stats.closed, kept_keys.count(row.key) > 0});
  const auto survey = workflow::survey_outline(store.geometry());
  const auto small = workflow::display_bodies(store, components, survey, 800);
  ASSERT_EQ(small.size(), kept.keys.size());
  std::size_t small_triangles = 0;
  for (const auto& b : small)
    small_triangles += b.triangles.size();
  EXPECT_LE(small_triangles, 800u);
  EXPECT_GT(small_triangles, 200u);

  // At most two bodies: the two kept ones with the most triangles, in the components' order, and
  // the whole budget is theirs.
  ASSERT_GT(kept.keys.size(), 2u);
  std::vector<const workflow::ReportComponent*> by_size;
  for (const auto& c : components)
    if (c.kept) by_size.push_back(&c);
  std::stable_sort(by_size.begin(), by_size.end(), [](auto* a, auto* b) { return a->triangles > b->triangles; });
  ASSERT_GT(by_size[1]->triangles, by_size[2]->triangles) << "the test needs a clear second largest";
  const auto two = workflow::display_bodies(store, components, survey, 800, 2);
  ASSERT_EQ(two.size(), 2u);
  std::vector<std::uint64_t> expected;
  for (const auto& c : components)
    if (&c == by_size[0] || &c == by_size[1]) expected.push_back(c.key);
  EXPECT_EQ((std::vector<std::uint64_t>{two[0].key, two[1].key}), expected);
  std::size_t two_triangles = 0;
  for (const auto& b : two)
    two_triangles += b.triangles.size();
  EXPECT_LE(two_triangles, 800u);
}

} // namespace
} // namespace geotandem
