// The example plugin (examples/custom_attribute), compiled into this test and called through its
// C descriptor as the host would: boxes against the whole cube (bit-identical), the whole cube
// against a brute-force oracle of the mirrored mean, and the error paths of the C boundary.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "geotandem/workflow/plugin_abi.h"

extern "C" const gt_plugin_descriptor* geotandem_plugin_entry(void);

namespace {

using Shape = std::array<std::int64_t, 3>;

struct Cube {
  Shape shape{};
  std::vector<float> values;
  float at(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return values[static_cast<std::size_t>((i * shape[1] + j) * shape[2] + k)];
  }
};

Cube random_cube(Shape shape, unsigned seed) {
  Cube c{shape, {}};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  c.values.resize(static_cast<std::size_t>(shape[0] * shape[1] * shape[2]));
  for (auto& v : c.values)
    v = u(rng);
  return c;
}

// Parameter values in spec order, as the host passes them after validation.
struct Params {
  Params(std::int64_t half_window, std::int64_t half_traces) {
    values[0].name = "half_window";
    values[0].int_value = half_window;
    values[1].name = "half_traces";
    values[1].int_value = half_traces;
    params.values = values;
    params.count = 2;
  }
  Params(const Params&) = delete;
  gt_param_value values[2]{};
  gt_params params{};
};

gt_cube_info info_of(const Cube& c) {
  gt_cube_info info{};
  for (int a = 0; a < 3; ++a)
    info.shape[a] = c.shape[a];
  info.dz = 4.0;
  info.z_unit_is_ms = 1;
  info.bin_i = info.bin_j = 25.0;
  return info;
}

std::int64_t volume_of(const gt_box& b) {
  return (b.hi[0] - b.lo[0]) * (b.hi[1] - b.lo[1]) * (b.hi[2] - b.lo[2]);
}

std::vector<float> samples_of(const Cube& c, const gt_box& b) {
  std::vector<float> out;
  for (std::int64_t i = b.lo[0]; i < b.hi[0]; ++i)
    for (std::int64_t j = b.lo[1]; j < b.hi[1]; ++j)
      for (std::int64_t k = b.lo[2]; k < b.hi[2]; ++k)
        out.push_back(c.at(i, j, k));
  return out;
}

class AvgAbsAmplitude : public ::testing::Test {
protected:
  const gt_plugin_descriptor& d = *geotandem_plugin_entry();

  Shape halo_of(const Params& p, const Cube& c) {
    gt_cube_info info = info_of(c);
    std::int64_t halo[3] = {-1, -1, -1};
    char error[256] = {0};
    EXPECT_EQ(d.attribute.halo(&p.params, &info, halo, error, sizeof error), 0) << error;
    return {halo[0], halo[1], halo[2]};
  }

  // Computes `box` as the host does: the input is the box grown by the halo, clipped to the cube.
  std::vector<float> compute(const Params& p, const Cube& c, const gt_box& box) {
    const Shape halo = halo_of(p, c);
    gt_box in{};
    for (int a = 0; a < 3; ++a) {
      in.lo[a] = std::max<std::int64_t>(0, box.lo[a] - halo[a]);
      in.hi[a] = std::min(c.shape[a], box.hi[a] + halo[a]);
    }
    std::vector<float> input = samples_of(c, in);
    std::vector<float> out(static_cast<std::size_t>(volume_of(box)), std::nanf(""));
    gt_cube_info info = info_of(c);
    char error[256] = {0};
    EXPECT_EQ(d.attribute.compute(&p.params, &info, input.data(), &in, out.data(), &box, error, sizeof error), 0)
        << error;
    return out;
  }
};

// Reflects g into [0, n) one bounce at a time: the textbook half-sample symmetric extension.
std::int64_t reflect(std::int64_t g, std::int64_t n) {
  while (g < 0 || g >= n)
    g = g < 0 ? -1 - g : 2 * n - 1 - g;
  return g;
}

double oracle(const Cube& c, std::int64_t i, std::int64_t j, std::int64_t k, std::int64_t hw, std::int64_t ht) {
  double sum = 0;
  for (std::int64_t a = -ht; a <= ht; ++a)
    for (std::int64_t b = -ht; b <= ht; ++b)
      for (std::int64_t s = -hw; s <= hw; ++s)
        sum += std::fabs(c.at(reflect(i + a, c.shape[0]), reflect(j + b, c.shape[1]), reflect(k + s, c.shape[2])));
  return sum / static_cast<double>((2 * ht + 1) * (2 * ht + 1) * (2 * hw + 1));
}

} // namespace

TEST_F(AvgAbsAmplitude, DescriptorIsWellFormed) {
  EXPECT_EQ(d.struct_size, sizeof(gt_plugin_descriptor));
  EXPECT_EQ(d.abi_major, static_cast<std::uint32_t>(GEOTANDEM_PLUGIN_ABI_MAJOR));
  EXPECT_STREQ(d.name, "avg_abs_amplitude");
  ASSERT_EQ(d.param_count, 2u);
  for (std::uint32_t n = 0; n < d.param_count; ++n) {
    const gt_param_spec& s = d.params[n];
    ASSERT_NE(s.default_value, nullptr) << s.name;
    const double v = std::stod(s.default_value);
    EXPECT_LE(s.min_value, v) << s.name;
    EXPECT_GE(s.max_value, v) << s.name;
    EXPECT_GT(std::strlen(s.help), 20u) << s.name;
  }
}

TEST_F(AvgAbsAmplitude, HaloIsTheHalfWindow) {
  Cube c = random_cube({9, 9, 9}, 1);
  EXPECT_EQ(halo_of(Params(7, 0), c), (Shape{0, 0, 7}));
  EXPECT_EQ(halo_of(Params(3, 2), c), (Shape{2, 2, 3}));
}

TEST_F(AvgAbsAmplitude, WholeCubeMatchesBruteForceMirroredMean) {
  // Windows wider than an axis (35 > 29 samples, 12 > 11 crosslines) reflect more than once.
  const Cube c = random_cube({13, 11, 29}, 2);
  const gt_box whole{{0, 0, 0}, {13, 11, 29}};
  for (auto [hw, ht] : {std::pair<int, int>{0, 0}, {3, 0}, {2, 1}, {35, 1}, {1, 12}}) {
    Params p(hw, ht);
    std::vector<float> out = compute(p, c, whole);
    std::size_t n = 0;
    double worst = 0;
    for (std::int64_t i = 0; i < 13; ++i)
      for (std::int64_t j = 0; j < 11; ++j)
        for (std::int64_t k = 0; k < 29; ++k)
          worst = std::max(worst, std::fabs(out[n++] - oracle(c, i, j, k, hw, ht)));
    EXPECT_LT(worst, 1e-6) << "half_window " << hw << ", half_traces " << ht;
  }
}

TEST_F(AvgAbsAmplitude, ConstantCubeGivesItsAbsoluteValueExactly) {
  Cube c = random_cube({5, 6, 7}, 3);
  std::fill(c.values.begin(), c.values.end(), -0.75f);
  Params p(4, 2);
  for (float v : compute(p, c, gt_box{{0, 0, 0}, {5, 6, 7}}))
    ASSERT_EQ(v, 0.75f);
}

TEST_F(AvgAbsAmplitude, BoxesAreBitIdenticalToTheWholeCube) {
  const Shape shape{17, 14, 31};
  const Cube c = random_cube(shape, 4);
  const gt_box whole{{0, 0, 0}, {shape[0], shape[1], shape[2]}};
  const std::vector<gt_box> boxes = {
      {{0, 0, 0}, {5, 4, 7}},       // corner: mirrored on three faces
      {{12, 10, 24}, {17, 14, 31}}, // opposite corner
      {{3, 5, 9}, {14, 9, 22}},     // interior, odd sizes
      {{0, 6, 30}, {17, 7, 31}},    // one crossline, one sample, on the last sample
      {{8, 0, 0}, {9, 14, 31}},     // a single inline across the cube
      {{1, 1, 1}, {2, 2, 2}},       // one sample, halo reaching past the faces
  };
  for (auto [hw, ht] : {std::pair<int, int>{0, 0}, {5, 0}, {3, 2}, {40, 9}}) {
    Params p(hw, ht);
    const std::vector<float> all = compute(p, c, whole);
    for (const gt_box& b : boxes) {
      const std::vector<float> part = compute(p, c, b);
      std::size_t n = 0;
      for (std::int64_t i = b.lo[0]; i < b.hi[0]; ++i)
        for (std::int64_t j = b.lo[1]; j < b.hi[1]; ++j)
          for (std::int64_t k = b.lo[2]; k < b.hi[2]; ++k) {
            const float w = all[static_cast<std::size_t>((i * shape[1] + j) * shape[2] + k)];
            ASSERT_EQ(std::memcmp(&part[n], &w, sizeof w), 0)
                << "sample (" << i << ", " << j << ", " << k << "): box " << part[n] << ", whole " << w
                << "; half_window " << hw << ", half_traces " << ht;
            ++n;
          }
    }
  }
}

TEST_F(AvgAbsAmplitude, ErrorsComeBackThroughTheBufferNotAsExceptions) {
  const Cube c = random_cube({8, 8, 8}, 5);
  gt_cube_info info = info_of(c);
  Params p(2, 1);
  // An input box that lacks the crossline halo the plugin asked for.
  const gt_box out{{2, 2, 2}, {6, 6, 6}};
  const gt_box in{{1, 2, 0}, {7, 6, 8}};
  std::vector<float> input = samples_of(c, in), output(64);
  char error[512];
  std::memset(error, 'x', sizeof error);
  int status = 0;
  EXPECT_NO_THROW(
      status = d.attribute.compute(&p.params, &info, input.data(), &in, output.data(), &out, error, sizeof error));
  EXPECT_NE(status, 0);
  ASSERT_NE(std::memchr(error, '\0', sizeof error), nullptr);
  EXPECT_NE(std::string(error).find("outside the input"), std::string::npos) << error;
  EXPECT_NE(std::string(error).find("crossline"), std::string::npos) << error;

  // A short buffer is truncated and still terminated.
  char tiny[8];
  std::memset(tiny, 'x', sizeof tiny);
  EXPECT_NE(d.attribute.compute(&p.params, &info, input.data(), &in, output.data(), &out, tiny, sizeof tiny), 0);
  EXPECT_EQ(std::strlen(tiny), sizeof tiny - 1);

  // Parameters the plugin did not declare.
  gt_params wrong{p.values, 1};
  std::int64_t halo[3];
  EXPECT_NE(d.attribute.halo(&wrong, &info, halo, error, sizeof error), 0);
  EXPECT_NE(std::string(error).find("expected 2 parameter values, got 1"), std::string::npos) << error;

  // An output box outside the cube.
  const gt_box outside{{6, 6, 6}, {9, 8, 8}};
  EXPECT_NE(d.attribute.compute(&p.params, &info, input.data(), &in, output.data(), &outside, error, sizeof error), 0);
  EXPECT_NE(std::string(error).find("inline axis"), std::string::npos) << error;
}
