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

TEST(Progress, StopSaysWhereItStoppedAndNotDone) {
  // An interrupted extraction must not end on "done". A line at every update (interval 0), none
  // with a time left: a test this fast is far from the 5 s an estimate waits for.
  std::ostringstream out;
  StreamProgress progress(out, false, std::chrono::milliseconds(0));
  progress.begin("extraction", 10, "blocks");
  progress.update(4);
  progress.stop();
  const std::string text = out.str();
  const std::string last = text.substr(text.rfind('\n', text.size() - 2) + 1);
  EXPECT_NE(last.find("40% (4/10 blocks)"), std::string::npos) << text;
  EXPECT_NE(last.find("stopped"), std::string::npos) << text;
  EXPECT_EQ(text.find("done"), std::string::npos) << text;
  EXPECT_EQ(text.find("left"), std::string::npos) << text;
}

TEST(Progress, TimeLeftFollowsTheRateSoFar) {
  // 10 s for a quarter: 30 s more.
  ASSERT_TRUE(seconds_left(10.0, 25, 100));
  EXPECT_DOUBLE_EQ(*seconds_left(10.0, 25, 100), 30.0);
  EXPECT_DOUBLE_EQ(*seconds_left(600.0, 1, 10), 5400.0);
  // Nothing while the rate says little, or when there is nothing left.
  EXPECT_FALSE(seconds_left(4.9, 50, 100)) << "before 5 s";
  EXPECT_FALSE(seconds_left(100.0, 1, 100)) << "before 2 % of the units";
  EXPECT_FALSE(seconds_left(100.0, 100, 100));
  EXPECT_FALSE(seconds_left(100.0, 0, 100));
  EXPECT_FALSE(seconds_left(100.0, 5, 0)) << "unknown total";
}

TEST(Progress, DurationsReadAsPeopleSayThem) {
  EXPECT_EQ(duration_text(0.4), "0 s");
  EXPECT_EQ(duration_text(42.4), "42 s");
  EXPECT_EQ(duration_text(59.6), "1 min");
  EXPECT_EQ(duration_text(89.0), "1 min");
  EXPECT_EQ(duration_text(91.0), "2 min");
  EXPECT_EQ(duration_text(3569.0), "59 min");
  EXPECT_EQ(duration_text(3600.0), "1 h 00 min");
  EXPECT_EQ(duration_text(5400.0 + 300.0), "1 h 35 min");
  EXPECT_EQ(duration_text(-3.0), "0 s");
}
