// Every sample is a pure function of its global index and the seed: a box read alone equals the
// same box cut from the whole cube, bit for bit, whatever its offset, size, reading order or thread.

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <thread>

#include "geotandem/synth/synthetic.hpp"

namespace geotandem::synth {
namespace {

struct Case {
  const char* kind;
  std::uint64_t seed;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.kind << " seed " << c.seed;
}

std::unique_ptr<SyntheticCube> make(const Case& c, const volume::Index3& shape) {
  if (std::string(c.kind) == "analytic") {
    AnalyticOptions o;
    o.shape = shape;
    o.seed = c.seed;
    return make_analytic(o);
  }
  SeismicOptions o;
  o.shape = shape;
  o.seed = c.seed;
  o.snr = 1.5; // noise on, so that its halo across traces and along the trace is exercised
  return make_seismic(o);
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

class Determinism : public ::testing::TestWithParam<Case> {};

TEST_P(Determinism, BoxesReadAloneEqualTheWholeCube) {
  const volume::Index3 shape{52, 47, 61};
  auto cube = make(GetParam(), shape);
  const auto whole = cube->read(cube->geometry().bounds());
  std::vector<volume::Box> boxes = {
      {{3, 5, 7}, {40, 37, 50}},    {{0, 0, 0}, {1, 47, 61}},  {{51, 46, 0}, {52, 47, 61}}, // one trace
      {{17, 0, 13}, {18, 47, 14}},  {{31, 1, 0}, {52, 2, 61}}, {{1, 1, 1}, {2, 2, 2}},      // one sample
      {{25, 23, 29}, {27, 25, 31}}, {{0, 0, 30}, {52, 47, 31}}};                            // a time slice
  std::mt19937_64 rng(GetParam().seed);
  for (int n = 0; n < 12; ++n) {
    volume::Box b;
    for (int a = 0; a < 3; ++a) {
      std::uniform_int_distribution<std::int64_t> lo(0, shape[a] - 1);
      b.lo[a] = lo(rng);
      std::uniform_int_distribution<std::int64_t> hi(b.lo[a] + 1, shape[a]);
      b.hi[a] = hi(rng);
    }
    boxes.push_back(b);
  }
  for (const auto& box : boxes) {
    const auto part = cube->read(box);
    std::vector<float> cut(box.count());
    volume::copy_region(whole.data(), cube->geometry().bounds(), cut.data(), box, box);
    EXPECT_TRUE(same_bits(part, cut)) << GetParam().kind << " seed " << GetParam().seed << " box " << box.to_string();
  }
}

TEST_P(Determinism, SameSeedSameBytesOtherSeedOtherCube) {
  const volume::Index3 shape{48, 44, 40};
  const auto a = make(GetParam(), shape)->read(volume::Box::of_shape(shape));
  const auto b = make(GetParam(), shape)->read(volume::Box::of_shape(shape));
  EXPECT_TRUE(same_bits(a, b));
  Case other = GetParam();
  other.seed += 1000;
  auto c_cube = make(other, shape);
  const auto c = c_cube->read(volume::Box::of_shape(shape));
  std::size_t differ = 0;
  for (std::size_t n = 0; n < a.size(); ++n)
    differ += a[n] != c[n];
  // The analytic background is the same function everywhere; bodies and bubbles move.
  EXPECT_GT(differ, a.size() / 20) << GetParam().kind;
  EXPECT_NE(make(GetParam(), shape)->truth().bodies[0].centre_index, c_cube->truth().bodies[0].centre_index);
}

TEST_P(Determinism, ConcurrentReadsAgreeWithSerialReads) {
  const volume::Index3 shape{64, 48, 40};
  auto cube = make(GetParam(), shape);
  const auto whole = cube->read(volume::Box::of_shape(shape));
  std::vector<std::vector<float>> parts(4);
  std::vector<std::thread> threads;
  for (std::int64_t t = 0; t < 4; ++t)
    threads.emplace_back([&, t] { parts[t] = cube->read(volume::Box{{16 * t, 0, 0}, {16 * t + 16, 48, 40}}); });
  for (auto& thread : threads)
    thread.join();
  for (std::int64_t t = 0; t < 4; ++t) {
    const volume::Box box{{16 * t, 0, 0}, {16 * t + 16, 48, 40}};
    std::vector<float> cut(box.count());
    volume::copy_region(whole.data(), volume::Box::of_shape(shape), cut.data(), box, box);
    EXPECT_TRUE(same_bits(parts[static_cast<std::size_t>(t)], cut)) << "slab " << t;
  }
}

INSTANTIATE_TEST_SUITE_P(Kinds, Determinism,
                         ::testing::Values(Case{"analytic", 1}, Case{"analytic", 77}, Case{"analytic", 123456789},
                                           Case{"seismic", 1}, Case{"seismic", 42}, Case{"seismic", 987654321}),
                         [](const ::testing::TestParamInfo<Case>& param_info) {
                           return std::string(param_info.param.kind) + "_" + std::to_string(param_info.param.seed);
                         });

TEST(Determinism, SeismicBoxesAgreeAtOtherFrequencies) {
  // A low frequency makes the wavelet reach 40 samples each way: boxes must still agree.
  SeismicOptions o;
  o.shape = {44, 40, 80};
  o.seed = 3;
  o.peak_frequency_hz = 8.0;
  auto cube = make_seismic(o);
  const auto whole = cube->read(cube->geometry().bounds());
  for (const volume::Box& box : {volume::Box{{5, 6, 0}, {9, 11, 7}}, volume::Box{{40, 0, 70}, {44, 3, 80}},
                                 volume::Box{{0, 39, 33}, {44, 40, 35}}}) {
    const auto part = cube->read(box);
    std::vector<float> cut(box.count());
    volume::copy_region(whole.data(), cube->geometry().bounds(), cut.data(), box, box);
    EXPECT_TRUE(same_bits(part, cut)) << box.to_string();
  }
}

} // namespace
} // namespace geotandem::synth

namespace geotandem::synth {
namespace {

// A seismic cube keeps the per-trace part of recent traces in a per-thread cache keyed by the
// cube: reading two cubes in turn (same shape, different seeds, so the same trace indices) must
// give each cube its own samples, as if read alone.
TEST(SeismicTraceCache, CubesReadInTurnKeepTheirOwnTraces) {
  const volume::Index3 shape{70, 66, 40};
  auto one = make({"seismic", 3}, shape);
  auto two = make({"seismic", 4}, shape);
  const auto two_whole = two->read(two->geometry().bounds());
  const volume::Box box{{1, 2, 0}, {69, 65, 40}};
  const auto first = one->read(box);
  const auto other = two->read(box);
  const auto again = one->read(box);
  EXPECT_TRUE(same_bits(first, again)) << "cube one changed after cube two was read";
  EXPECT_FALSE(same_bits(first, other)) << "two seeds gave the same samples: the test could not fail";
  std::size_t n = 0;
  for (auto i = box.lo[0]; i < box.hi[0]; ++i)
    for (auto j = box.lo[1]; j < box.hi[1]; ++j)
      for (auto k = box.lo[2]; k < box.hi[2]; ++k, ++n)
        ASSERT_EQ(other[n], two_whole[static_cast<std::size_t>((i * shape[1] + j) * shape[2] + k)])
            << "cube two at (" << i << ", " << j << ", " << k << ")";
  // A fresh cube of seed 3 (a new cache key) agrees with the first one.
  EXPECT_TRUE(same_bits(make({"seismic", 3}, shape)->read(box), first));
}

} // namespace
} // namespace geotandem::synth
