// The seismic kind's white noise (framework/synth/src/seismic.cpp) computes the hash four samples
// at a time; every value must have the bits of the scalar formula it replaced.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "hash.hpp"
#include "white_noise.hpp"

namespace geotandem::synth::detail {
namespace {

TEST(WhiteNoise, EveryValueHasTheBitsOfTheScalarHash) {
  LayoutRng rng(20261202);
  std::size_t checked = 0;
  double sum = 0.0, sum2 = 0.0;
  for (int trial = 0; trial < 400; ++trial) {
    const std::uint64_t key = rng.next();
    const auto k0 = static_cast<std::int64_t>(rng.uniform(-3000.0, 3000.0));
    const auto n = static_cast<std::int64_t>(rng.uniform(0.0, 41.0)); // remainders 0 to 3 included
    std::vector<float> got(static_cast<std::size_t>(n) + 1, 1234.5f);
    white_noise(key, k0, n, got.data());
    for (std::int64_t k = 0; k < n; ++k) {
      const auto want = static_cast<float>(uniform(hash1(key, k0 + k), -1.7320508075688772, 1.7320508075688772));
      const float value = got[static_cast<std::size_t>(k)];
      ASSERT_EQ(std::memcmp(&value, &want, sizeof value), 0)
          << "key " << key << ", sample " << k0 + k << ": " << value << " against " << want;
      sum += value;
      sum2 += static_cast<double>(value) * value;
      ++checked;
    }
    EXPECT_EQ(got[static_cast<std::size_t>(n)], 1234.5f) << "wrote past n = " << n;
  }
  ASSERT_GT(checked, 5000u);
  const double mean = sum / static_cast<double>(checked);
  EXPECT_NEAR(mean, 0.0, 0.05);
  EXPECT_NEAR(sum2 / static_cast<double>(checked) - mean * mean, 1.0, 0.05); // unit variance
}

} // namespace
} // namespace geotandem::synth::detail
