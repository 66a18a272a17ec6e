#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fixtures.hpp"
#include "geotandem/attributes/rms.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::attributes {
namespace {

using testing::cube;
using testing::noise;
using testing::reflect;

TEST(Rms, BoxAloneEqualsWholeCube) {
  auto u = cube({24, 20, 64}, [](int i, int j, int k) { return noise(i, j, k) * (1.0 + 0.1 * i); });
  testing::expect_boxes_match_whole(Rms(u));
  testing::expect_boxes_match_whole(Rms(u, {.window = 1}));
  testing::expect_boxes_match_whole(Rms(u, {.window = 31}));
}

TEST(Rms, OfACosineOverWholePeriodsIsAmplitudeOverRootTwo) {
  // Over a whole number of periods (N > 2 samples), the mean of cos^2 is exactly 1/2.
  const double amplitude = 2.0;
  auto u = cube({2, 3, 60}, [&](int i, int j, int k) {
    return amplitude * std::cos(2 * std::numbers::pi * k / 9.0 + 0.4 * i + 0.9 * j);
  });
  const std::vector<float> r = Rms(u, {.window = 9}).read(u->geometry().bounds());
  for (int line = 0; line < 6; ++line)
    for (int k = 4; k < 56; ++k)
      ASSERT_NEAR(r[static_cast<std::size_t>(line * 60 + k)], amplitude / std::sqrt(2.0), 1e-5) << line << " " << k;
}

TEST(Rms, MatchesDirectSumOverTheMirroredWindow) {
  const int nk = 30;
  auto u = cube({2, 2, nk}, [](int i, int j, int k) { return 3.0 * noise(i, j, k, 3); });
  for (int window : {1, 5, 11}) {
    const std::vector<float> r = Rms(u, {.window = window}).read(u->geometry().bounds());
    for (int line = 0; line < 4; ++line)
      for (int k = 0; k < nk; ++k) {
        double sum = 0.0;
        for (int t = -window / 2; t <= window / 2; ++t) {
          const double v = 3.0 * noise(line / 2, line % 2, reflect(k + t, nk), 3);
          sum += v * v;
        }
        ASSERT_NEAR(r[static_cast<std::size_t>(line * nk + k)], std::sqrt(sum / window), 1e-5)
            << "window " << window << " trace " << line << " k " << k;
      }
  }
}

TEST(Rms, RejectsABadWindowNamingItAndItsRange) {
  auto u = cube({4, 4, 16}, [](int, int, int k) { return k; });
  for (int bad : {8, 0, -1, 1003}) {
    try {
      Rms(u, {.window = bad});
      FAIL() << "window " << bad << " was accepted";
    } catch (const InvalidArgument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("'window'"), std::string::npos) << what;
      EXPECT_NE(what.find("odd integer in [1, 1001]"), std::string::npos) << what;
    }
  }
}

} // namespace
} // namespace geotandem::attributes
