// The seismic generator's own exp (framework/synth/src/fast_exp.hpp) against the C library's.

#include <gtest/gtest.h>

#include <cmath>

#include "fast_exp.hpp"

namespace geotandem::synth::detail {
namespace {

TEST(FastExp, MatchesTheCLibraryToAFewUlps) {
  double worst = 0.0;
  for (int n = -700000; n <= 700000; ++n) {
    const double y = n * 1e-3 + 1e-7 * (n % 7); // not only round arguments
    const double want = std::exp(y);
    const double rel = std::abs(fast_exp(y) - want) / want;
    worst = std::max(worst, rel);
    ASSERT_LE(rel, 1e-15) << "y = " << y;
  }
  EXPECT_EQ(fast_exp(0.0), 1.0);
  RecordProperty("worst_relative_error", std::to_string(worst));
}

TEST(FastExp, ClampsFarArgumentsInsteadOfOverflowing) {
  EXPECT_GT(fast_exp(-1000.0), 0.0);
  EXPECT_LT(fast_exp(-1000.0), 1e-300);
  EXPECT_TRUE(std::isfinite(fast_exp(1000.0)));
  EXPECT_GT(fast_exp(1000.0), 1e300);
}

} // namespace
} // namespace geotandem::synth::detail
