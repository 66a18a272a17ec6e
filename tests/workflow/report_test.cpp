// The run report: self-contained HTML whose plots reflect the data given.

#include <gtest/gtest.h>

#include <regex>

#include "geotandem/workflow/report.hpp"

using namespace geotandem::workflow;

namespace {

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
    ++n;
  return n;
}

} // namespace

TEST(Report, RoseDrawsEachNonEmptyBinTwice) {
  // 3 distinct bins of 10 degrees: 5, 95, 175 (and 174.9 in the same bin as 175).
  std::string svg = svg_rose({5.0, 95.0, 175.0, 174.9}, {}, 18);
  EXPECT_EQ(count_of(svg, "class=\"petal\""), 6u) << svg;
  EXPECT_NE(svg.find("4 components"), std::string::npos);
  // Axial: 185 degrees is the same direction as 5.
  EXPECT_EQ(count_of(svg_rose({5.0, 185.0}, {}, 18), "class=\"petal\""), 2u);
}

TEST(Report, HistogramMarksThresholdAndGreysRemovedBars) {
  std::vector<double> volumes = {0.5, 0.7, 0.9, 1.1, 2e4, 3e4, 5e5};
  std::string svg = svg_volume_histogram(volumes, 100.0, "m^3");
  EXPECT_EQ(count_of(svg, "class=\"threshold\""), 1u);
  EXPECT_GE(count_of(svg, "fill=\"#c9c9c9\""), 1u) << "bubbles below the threshold are drawn grey";
  EXPECT_GE(count_of(svg, "fill=\"#2b7bb9\""), 1u) << "kept bodies are drawn blue";
  EXPECT_EQ(svg_volume_histogram({}, 0, "m^3").find("class=\"bar\""), std::string::npos);
}

TEST(Report, PageIsSelfContainedAndEscaped) {
  ReportData d;
  d.title = "quickstart <test>";
  d.recipe = {{"input", "<cube & more>"}};
  d.steps = {{"extract", 1.5, 0, 120, ""}, {"remove_bubbles", 0.01, 120, 4, "min_volume_fraction 0.01"}};
  for (int n = 0; n < 120; ++n)
    d.components.push_back(
        {static_cast<std::uint64_t>(n), n < 4 ? 1e6 * (n + 1) : 10.0 + n, 30.0 + n, 0.5, 100, true, n < 4});
  d.bubble_threshold = 1e4;
  d.triangles_per_layer = {0, 10, 200, 150, 50};
  std::string html = render_report(d);
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("src=\"http"), std::string::npos) << "no external resources";
  EXPECT_NE(html.find("quickstart &lt;test&gt;"), std::string::npos);
  EXPECT_NE(html.find("&lt;cube &amp; more&gt;"), std::string::npos);
  EXPECT_EQ(count_of(html, "<svg"), 3u);
  EXPECT_NE(html.find("120 components extracted, <span class=\"kept\">4 kept"), std::string::npos);
  // The largest table lists the 4 kept bodies first, by volume.
  std::regex first_row("<tr><td>1</td><td>3</td>");
  EXPECT_TRUE(std::regex_search(html, first_row)) << "largest component first";
  EXPECT_EQ(count_of(html, "class=\"l kept\""), 4u);
}
