// What the report must not hide: a kept body cut by the border (it has no enclosed volume), and
// an execution section the build does not honour.

#include <gtest/gtest.h>

#include "geotandem/workflow/report.hpp"

using namespace geotandem::workflow;

TEST(ReportContents, KeptBodiesCutByTheBorderAreListed) {
  ReportData d;
  d.volume_unit = "m^2*ms";
  for (int n = 0; n < 60; ++n)
    d.components.push_back({static_cast<std::uint64_t>(100 + n), 5.0 + n, 10.0, 0.2, 8, true, false});
  d.components.push_back({7, 2e6, 45.0, 0.8, 900, true, true});
  d.components.push_back({9, 0.0, 120.0, 0.7, 700, false, true});         // cut by the border, kept (store before caps)
  d.components.push_back({11, 3e5, 60.0, 0.5, 400, true, true, "i-,k+"}); // closed by caps
  std::string html = render_report(d);
  EXPECT_NE(html.find("cut i-,k+, capped"), std::string::npos);
  EXPECT_NE(html.find("<td>3e+05</td>"), std::string::npos) << "a capped body has its volume";
  EXPECT_NE(html.find("<tr><td>3</td><td>9</td>"), std::string::npos)
      << "the kept component cut by the border is missing";
  EXPECT_NE(html.find("cut by border"), std::string::npos);
  EXPECT_NE(html.find("m\u00b2\u00b7ms"), std::string::npos) << "units are written as a reader writes them";
  EXPECT_EQ(html.find("m^2*ms"), std::string::npos);
}

TEST(ReportContents, ExecutionTheBuildDoesNotHonourIsStated) {
  ReportData d;
  d.recipe = {{"execution", {{"scheduler", "slurm"}, {"workers", 8}}},
              {"input", {{"synthetic", {{"kind", "seismic"}, {"shape", {128, 128, 96}}, {"seed", 3}, {"snr", 4.0}}}}}};
  std::string html = render_report(d);
  EXPECT_NE(html.find("scheduler <b>slurm</b> with 8 worker(s)"), std::string::npos);
  EXPECT_NE(html.find("ran in this process"), std::string::npos);
  EXPECT_NE(html.find("128 &times; 128 &times; 96 samples, seed 3"), std::string::npos);
}
