#include <gtest/gtest.h>

#include <sstream>

#include "geotandem/core/progress.hpp"

using namespace geotandem;

TEST(Progress, PlainLinesAtEachTenPercent) {
  std::ostringstream out;
  StreamProgress progress(out, false, std::chrono::hours(1));
  progress.begin("extracting", 100, "layers");
  for (int n = 0; n < 100; ++n)
    progress.advance();
  progress.end();
  std::string text = out.str();
  // start line, 9 decile lines (10 % .. 90 %), final line
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 11) << text;
  EXPECT_NE(text.find("extracting: 50% (50/100 layers)"), std::string::npos) << text;
  EXPECT_NE(text.find("100% (100/100 layers)"), std::string::npos) << text;
  EXPECT_NE(text.find("done"), std::string::npos);
}

TEST(Progress, FewUnitsGiveNoDecileLines) {
  // Eight components exported in a blink: "started" and "done", not a line per component.
  std::ostringstream out;
  StreamProgress progress(out, false, std::chrono::hours(1));
  progress.begin("exporting", 8, "components");
  for (int n = 0; n < 8; ++n)
    progress.advance();
  progress.end();
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2) << text;
  EXPECT_NE(text.find("100% (8/8 components)"), std::string::npos) << text;
}

TEST(Progress, BarRedrawsInPlace) {
  std::ostringstream out;
  StreamProgress progress(out, true);
  progress.begin("reading", 4, "blocks");
  progress.update(4);
  progress.end();
  std::string text = out.str();
  EXPECT_NE(text.find('\r'), std::string::npos);
  EXPECT_NE(text.find("[##############################]"), std::string::npos) << text;
  EXPECT_EQ(text.back(), '\n');
}

TEST(Progress, UpdatesNeverGoBackwards) {
  std::ostringstream out;
  StreamProgress progress(out, false, std::chrono::hours(1));
  progress.begin("x", 10, "u");
  progress.update(5);
  progress.update(3);
  progress.end();
  EXPECT_NE(out.str().find("(5/10 u)"), std::string::npos) << out.str();
}
