#pragma once
// Small cubes from formulas, deterministic noise, and the box-versus-whole-cube check shared by
// the attribute tests.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "geotandem/volume/volume.hpp"

namespace geotandem::attributes::testing {

using volume::Box;
using volume::Index3;
using volume::MemoryVolume;

// A memory cube whose sample (i, j, k) is f(i, j, k).
inline std::shared_ptr<MemoryVolume> cube(const Index3& shape, const std::function<double(int, int, int)>& f) {
  volume::Geometry g;
  g.shape = shape;
  std::vector<float> samples;
  samples.reserve(g.sample_count());
  for (int i = 0; i < shape[0]; ++i)
    for (int j = 0; j < shape[1]; ++j)
      for (int k = 0; k < shape[2]; ++k)
        samples.push_back(static_cast<float>(f(i, j, k)));
  return std::make_shared<MemoryVolume>(g, std::move(samples), "test cube");
}

// Deterministic white noise in [-1, 1) from a hash of (i, j, k, seed) (splitmix64).
inline double noise(int i, int j, int k, std::uint64_t seed = 1) {
  std::uint64_t x = seed * 0x9E3779B97F4A7C15ull ^ (static_cast<std::uint64_t>(i) << 42) ^
                    (static_cast<std::uint64_t>(j) << 21) ^ static_cast<std::uint64_t>(k);
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  x ^= x >> 31;
  return static_cast<double>(x >> 11) / static_cast<double>(1ull << 52) - 1.0;
}

// Half-sample symmetric mirror, written independently of the library's.
inline int reflect(int m, int n) {
  while (m < 0 || m >= n)
    m = m < 0 ? -m - 1 : 2 * n - 1 - m;
  return m;
}

// Boxes of odd sizes at the corners, on each face and inside a cube of `shape` (each axis >= 9),
// plus a single voxel and one whole trace.
inline std::vector<Box> probe_boxes(const Index3& s) {
  auto box = [](Index3 lo, Index3 hi) { return Box{lo, hi}; };
  const std::int64_t ci = s[0] / 2, cj = s[1] / 2, ck = s[2] / 2;
  return {
      box({0, 0, 0}, {5, 7, 9}),                                 // corner at the origin
      box({s[0] - 5, s[1] - 7, s[2] - 9}, s),                    // far corner
      box({0, s[1] - 3, s[2] - 7}, {3, s[1], s[2]}),             // mixed corner
      box({0, cj - 3, ck - 5}, {7, cj + 4, ck + 6}),             // near inline face
      box({s[0] - 3, cj - 6, ck - 11}, {s[0], cj + 7, ck + 12}), // far inline face
      box({ci - 3, 0, ck - 6}, {ci + 4, 5, ck + 7}),             // near crossline face
      box({ci - 2, s[1] - 5, ck - 4}, {ci + 3, s[1], ck + 5}),   // far crossline face
      box({ci - 2, cj - 3, 0}, {ci + 3, cj + 4, 11}),            // top of the traces
      box({ci - 2, cj - 3, s[2] - 7}, {ci + 3, cj + 4, s[2]}),   // bottom of the traces
      box({ci - 2, cj - 4, ck - 6}, {ci + 3, cj + 5, ck + 7}),   // interior
      box({ci, cj, ck}, {ci + 1, cj + 1, ck + 1}),               // one voxel
      box({1, 2, 0}, {2, 3, s[2]}),                              // one whole trace
  };
}

// Every probe box read alone equals, bit for bit, the same box of the whole-cube result.
inline void expect_boxes_match_whole(const volume::Volume& attribute) {
  const Box bounds = attribute.geometry().bounds();
  const std::vector<float> whole = attribute.read(bounds);
  for (const Box& box : probe_boxes(bounds.shape())) {
    const std::vector<float> part = attribute.read(box);
    std::size_t mismatches = 0;
    for (std::int64_t i = box.lo[0]; i < box.hi[0]; ++i)
      for (std::int64_t j = box.lo[1]; j < box.hi[1]; ++j)
        for (std::int64_t k = box.lo[2]; k < box.hi[2]; ++k) {
          const float a = part[box.offset({i, j, k})], b = whole[bounds.offset({i, j, k})];
          if (a != b && mismatches++ == 0)
            ADD_FAILURE() << attribute.source() << ": box " << box.to_string() << " at (" << i << ", " << j << ", " << k
                          << ") gives " << a << " alone and " << b << " in the whole cube";
        }
    EXPECT_EQ(mismatches, 0u) << "box " << box.to_string();
  }
}

} // namespace geotandem::attributes::testing
