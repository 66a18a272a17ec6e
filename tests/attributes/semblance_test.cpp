#include <gtest/gtest.h>

#include <cmath>

#include "fixtures.hpp"
#include "geotandem/attributes/semblance.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::attributes {
namespace {

using testing::cube;
using testing::noise;
using testing::reflect;

TEST(Semblance, BoxAloneEqualsWholeCube) {
  auto u = cube({24, 20, 64}, [](int i, int j, int k) { return std::sin(0.25 * k + 0.05 * i * j) + noise(i, j, k); });
  testing::expect_boxes_match_whole(Semblance(u));
  testing::expect_boxes_match_whole(Semblance(u, {.traces = 5, .window = 3}));
}

TEST(Semblance, IdenticalTracesGiveOne) {
  auto u = cube({24, 20, 64}, [](int, int, int k) { return std::sin(0.3 * k) + 0.3 * noise(0, 0, k); });
  const std::vector<float> s = Semblance(u).read(u->geometry().bounds());
  for (float v : s)
    ASSERT_NEAR(v, 1.0f, 1e-5f);
}

TEST(Semblance, RandomTracesGiveLowValues) {
  // For independent traces the expected semblance is about 1/M = 1/9 (plus the window's spread).
  auto u = cube({24, 20, 64}, [](int i, int j, int k) { return noise(i, j, k, 11); });
  const std::vector<float> s = Semblance(u).read(u->geometry().bounds());
  double mean = 0.0;
  for (float v : s) {
    ASSERT_GE(v, 0.0f);
    ASSERT_LE(v, 1.0f);
    mean += v;
  }
  mean /= static_cast<double>(s.size());
  EXPECT_LT(mean, 0.25);
  EXPECT_GT(mean, 0.05);
}

TEST(Semblance, MatchesTheDefinitionOnMirroredNeighbours) {
  const Index3 shape{5, 4, 20};
  auto u = cube(shape, [](int i, int j, int k) { return noise(i, j, k, 2) + 0.5 * std::cos(0.5 * k); });
  const std::vector<float> s = Semblance(u, {.traces = 3, .window = 7}).read(u->geometry().bounds());
  std::size_t n = 0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 20; ++k, ++n) {
        double numerator = 0.0, energy = 0.0;
        for (int t = -3; t <= 3; ++t) {
          double stack = 0.0;
          for (int a = -1; a <= 1; ++a)
            for (int b = -1; b <= 1; ++b) {
              const double f = noise(reflect(i + a, 5), reflect(j + b, 4), reflect(k + t, 20), 2) +
                               0.5 * std::cos(0.5 * reflect(k + t, 20));
              stack += f;
              energy += f * f;
            }
          numerator += stack * stack;
        }
        ASSERT_NEAR(s[n], numerator / (9.0 * energy), 2e-5) << i << ", " << j << ", " << k;
      }
}

TEST(Semblance, ZeroInputGivesOne) {
  auto u = cube({4, 4, 12}, [](int, int, int) { return 0.0; });
  for (float v : Semblance(u).read(u->geometry().bounds()))
    EXPECT_EQ(v, 1.0f);
}

TEST(Semblance, RejectsBadApertureOrWindow) {
  auto u = cube({4, 4, 16}, [](int, int, int k) { return k; });
  for (auto [options, name, range] : {std::tuple{SemblanceOptions{.traces = 2}, "'traces'", "[3, 21]"},
                                      std::tuple{SemblanceOptions{.traces = 1}, "'traces'", "[3, 21]"},
                                      std::tuple{SemblanceOptions{.window = 4}, "'window'", "[1, 1001]"},
                                      std::tuple{SemblanceOptions{.window = -9}, "'window'", "[1, 1001]"}}) {
    try {
      Semblance s(u, options);
      FAIL() << name << " accepted";
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(range), std::string::npos) << e.what();
    }
  }
}

} // namespace
} // namespace geotandem::attributes
