#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fixtures.hpp"
#include "geotandem/attributes/envelope.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::attributes {
namespace {

using testing::cube;
using testing::noise;
using testing::reflect;

const double pi = std::numbers::pi;

TEST(Envelope, BoxAloneEqualsWholeCube) {
  auto u = cube({24, 20, 64}, [](int i, int j, int k) { return std::cos(0.3 * k + 0.2 * i) + 0.5 * noise(i, j, k); });
  testing::expect_boxes_match_whole(Envelope(u));
  testing::expect_boxes_match_whole(Envelope(u, {.half_length = 7}));
}

// The envelope of A cos(2 pi f k + phase) is A. Tolerance: the default transformer's gain G is
// within 3.5e-4 of 1 for 0.05 <= f <= 0.45 (the kernel test checks 4e-4), and the computed envelope
// sqrt(cos^2 + G^2 sin^2) A lies between A and G A where the whole filter lies inside the trace;
// float rounding of 33 products adds about 1e-6 A. 1e-3 A leaves a margin and still fails for a
// wrong tap, an untapered transformer (Gibbs ripple of about 5 percent) or a misaligned transform.
TEST(Envelope, OfACosineIsConstantAwayFromTheEnds) {
  const double amplitude = 3.0;
  for (double f : {0.0625, 0.2, 0.41}) {
    auto u = cube({3, 2, 256},
                  [&](int i, int j, int k) { return amplitude * std::cos(2 * pi * f * k + 0.7 * i + 1.3 * j); });
    Envelope envelope(u);
    const std::vector<float> e = envelope.read(u->geometry().bounds());
    for (int line = 0; line < 6; ++line)
      for (int k = 32; k < 256 - 32; ++k)
        ASSERT_NEAR(e[static_cast<std::size_t>(line * 256 + k)], amplitude, 1e-3 * amplitude)
            << "f " << f << " trace " << line << " k " << k;
  }
}

TEST(Envelope, OfAConstantIsItsMagnitudeEverywhere) {
  // A constant mirrors to itself and the odd transformer cancels it exactly, up to the trace ends.
  auto u = cube({2, 3, 40}, [](int i, int, int) { return i == 0 ? -2.5 : 4.0; });
  const std::vector<float> e = Envelope(u).read(u->geometry().bounds());
  for (std::size_t n = 0; n < e.size(); ++n)
    EXPECT_EQ(e[n], n < 120 ? 2.5f : 4.0f) << n;
}

TEST(Envelope, MatchesDirectConvolutionOfTheMirroredTrace) {
  const int nk = 48, half = 12;
  auto u = cube({2, 2, nk}, [](int i, int j, int k) { return noise(i, j, k, 5); });
  const std::vector<float> e = Envelope(u, {.half_length = half}).read(u->geometry().bounds());
  for (int line = 0; line < 4; ++line)
    for (int k = 0; k < nk; ++k) {
      double h = 0.0;
      for (int n = -half; n <= half; n += 1) {
        if (n % 2 == 0) continue;
        const double x = std::abs(n) / (half + 1.0);
        const double window = 0.42 + 0.5 * std::cos(pi * x) + 0.08 * std::cos(2 * pi * x);
        h += 2.0 / (pi * n) * window * noise(line / 2, line % 2, reflect(k - n, nk), 5);
      }
      const double v = noise(line / 2, line % 2, k, 5);
      ASSERT_NEAR(e[static_cast<std::size_t>(line * nk + k)], std::hypot(v, h), 1e-5) << "trace " << line << " k " << k;
    }
}

TEST(Envelope, HaloIsTheHalfLengthAlongTheTrace) {
  auto u = cube({4, 4, 16}, [](int, int, int k) { return k; });
  EXPECT_EQ(Envelope(u, {.half_length = 20}).halo(), (Index3{0, 0, 20}));
  // Halos longer than the trace still work: the mirror repeats.
  testing::expect_boxes_match_whole(
      Envelope(cube({16, 16, 24}, [](int i, int j, int k) { return noise(i, j, k); }), {.half_length = 40}));
}

TEST(Envelope, RejectsABadHalfLengthNamingItAndItsRange) {
  auto u = cube({4, 4, 16}, [](int, int, int k) { return k; });
  for (int bad : {1, 0, -3, 513}) {
    try {
      Envelope(u, {.half_length = bad});
      FAIL() << "half_length " << bad << " was accepted";
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find("half_length"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("[2, 512]"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(Envelope(nullptr), InvalidArgument);
}

} // namespace
} // namespace geotandem::attributes
