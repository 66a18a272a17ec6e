// A worker's walltime (framework/runtime/src/walltime.cpp): when it stops taking tasks, through its
// environment as a scheduler's job sets it. The clock starts when the library is loaded (here: when
// this test process starts).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

#include "../../framework/runtime/src/walltime.hpp"

namespace geotandem::runtime::detail {
namespace {

// About when the walltime's clock started (both are set before main).
const auto process_start = std::chrono::steady_clock::now();

class WalltimeEnv : public ::testing::Test {
protected:
  void SetUp() override {
    ::unsetenv(walltime_variable);
    ::unsetenv(walltime_margin_variable);
  }
  void TearDown() override { SetUp(); }
  static void set(const char* name, const std::string& value) { ::setenv(name, value.c_str(), 1); }
};

TEST_F(WalltimeEnv, WithoutAWalltimeAWorkerNeverStops) {
  EXPECT_EQ(walltime_exhausted(), "");
  EXPECT_FALSE(walltime_nearly_over());
}

// The default margin keeps a long job's figures (5 %, 60 s to 10 min) and never takes more than a
// quarter of a short one: with 60 s, a job of 30 s would have retired after its first task.
TEST_F(WalltimeEnv, TheDefaultMarginLeavesAShortJobMostOfItsTime) {
  for (const double walltime : {4.0, 30.0, 120.0, 239.0, 240.0, 600.0, 1200.0, 3600.0, 12000.0, 86400.0}) {
    const double margin = walltime_margin(walltime);
    EXPECT_GT(margin, 0.0) << walltime;
    EXPECT_LE(margin, walltime / 4) << walltime;
    EXPECT_LE(margin, 600.0) << walltime;
    if (walltime >= 240.0) {
      EXPECT_GE(margin, 60.0) << walltime;
    }
    if (walltime >= 1200.0 && walltime <= 12000.0) {
      EXPECT_DOUBLE_EQ(margin, walltime / 20) << walltime;
    }
  }
  // A 30 s job, just started, takes tasks.
  set(walltime_variable, "30");
  EXPECT_EQ(walltime_exhausted(), "");
  EXPECT_FALSE(walltime_nearly_over());
}

// With a 2 s walltime (margin 0.5 s), the worker stops taking tasks after 1.5 s and gives up
// waiting for a successor after 1.75 s; the message says how long is left.
TEST_F(WalltimeEnv, AWorkerStopsAMarginBeforeItsWalltime) {
  set(walltime_variable, "2");
  const std::string early = walltime_exhausted();
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - process_start).count();
  if (elapsed < 1.0) { // well within the first 1.5 s of the process (not so when run after slow tests)
    EXPECT_EQ(early, "");
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1800));
  const std::string late = walltime_exhausted();
  EXPECT_NE(late.find("left of its 2.0 s walltime (it stops 0.5 s before)"), std::string::npos) << late;
  EXPECT_TRUE(walltime_nearly_over());
  // An explicit margin wins, and a malformed one is ignored (the default then).
  set(walltime_variable, "1000");
  set(walltime_margin_variable, "999.5");
  EXPECT_NE(walltime_exhausted().find("(it stops 999 s before)"), std::string::npos) << walltime_exhausted();
  set(walltime_margin_variable, "ten");
  EXPECT_EQ(walltime_exhausted(), "");
}

} // namespace
} // namespace geotandem::runtime::detail
