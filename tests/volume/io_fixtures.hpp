#pragma once
// Small formula cubes for the SEG-Y, raw and detection tests. Every sample's value encodes its
// index, so a sample read from the wrong place shows. Values are multiples of 1/64 below 1024 in
// magnitude: exact in IEEE and in IBM floats, so comparisons can be exact.

#include <gtest/gtest.h>

#include <cstdint>
#include <exception>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "geotandem/volume/volume.hpp"

namespace geotandem::volume::testing {

// Unique per (i, j, k) while j < 100 and k < 64.
inline float formula(std::int64_t i, std::int64_t j, std::int64_t k) {
  return static_cast<float>(100 * i + j) + static_cast<float>(k) / 64.0f - 300.0f;
}

inline std::vector<float> formula_samples(const Box& box) {
  std::vector<float> out;
  out.reserve(box.count());
  for (std::int64_t i = box.lo[0]; i < box.hi[0]; ++i)
    for (std::int64_t j = box.lo[1]; j < box.hi[1]; ++j)
      for (std::int64_t k = box.lo[2]; k < box.hi[2]; ++k)
        out.push_back(formula(i, j, k));
  return out;
}

// A geometry with no default left: a rotated, non-square grid, odd line numbers and origins.
inline Geometry sample_geometry(Index3 shape = {7, 9, 50}) {
  Geometry g;
  g.shape = shape;
  g.inline0 = 1200;
  g.inline_step = -2;
  g.crossline0 = 35;
  g.crossline_step = 3;
  g.z0 = 12;
  g.dz = 2;
  g.affine = SurveyAffine{431250.25, 10.5, -6.25, 6712040.5, 6.25, 12.5};
  return g;
}

inline std::unique_ptr<MemoryVolume> formula_cube(const Geometry& g) {
  return std::make_unique<MemoryVolume>(g, formula_samples(g.bounds()), "formula cube");
}

// Boxes that exercise every kind of contiguity: whole cube, whole inlines, whole traces, parts of
// traces, single samples, the far corner. Boxes that reach past a small cube are clipped to it.
inline std::vector<Box> probe_boxes(const Index3& s) {
  const std::vector<Box> wanted = {
      Box::of_shape(s),
      Box{{1, 0, 0}, {3, s[1], s[2]}},
      Box{{0, 2, 0}, {s[0], 5, s[2]}},
      Box{{2, 1, 7}, {5, 8, 31}},
      Box{{s[0] - 1, s[1] - 1, s[2] - 1}, s},
      Box{{3, 4, 0}, {4, 5, s[2]}},
      Box{{0, 0, 5}, {s[0], s[1], 6}},
  };
  std::vector<Box> boxes;
  for (const Box& box : wanted)
    if (Box clipped = box.intersection(Box::of_shape(s)); !clipped.empty()) boxes.push_back(clipped);
  return boxes;
}

inline void expect_near_affine(const SurveyAffine& a, const SurveyAffine& b, double tolerance) {
  EXPECT_NEAR(a.x0, b.x0, tolerance);
  EXPECT_NEAR(a.xi, b.xi, tolerance);
  EXPECT_NEAR(a.xj, b.xj, tolerance);
  EXPECT_NEAR(a.y0, b.y0, tolerance);
  EXPECT_NEAR(a.yi, b.yi, tolerance);
  EXPECT_NEAR(a.yj, b.yj, tolerance);
}

// The same grid and sample axis: shape, line numbers and their steps, first sample and interval.
inline void expect_same_grid(const Geometry& a, const Geometry& b) {
  EXPECT_EQ(a.shape, b.shape);
  EXPECT_EQ(a.inline0, b.inline0);
  EXPECT_EQ(a.inline_step, b.inline_step);
  EXPECT_EQ(a.crossline0, b.crossline0);
  EXPECT_EQ(a.crossline_step, b.crossline_step);
  EXPECT_EQ(a.z0, b.z0);
  EXPECT_EQ(a.dz, b.dz);
}

// Two affines place the four corner traces of a grid of `shape` within `tolerance` metres.
inline void expect_near_at_corners(const SurveyAffine& a, const SurveyAffine& b, const Index3& shape,
                                   double tolerance) {
  const double ni = static_cast<double>(shape[0] - 1), nj = static_cast<double>(shape[1] - 1);
  for (auto [i, j] : {std::array<double, 2>{0, 0}, {ni, 0}, {0, nj}, {ni, nj}})
    for (std::size_t axis = 0; axis < 2; ++axis)
      EXPECT_NEAR(a.apply(i, j)[axis], b.apply(i, j)[axis], tolerance) << "(" << i << ", " << j << ")";
}

inline void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

inline std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The message of the E that `action` throws; a test failure when it throws nothing or another type.
template <class E> std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const E& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return {};
  }
  ADD_FAILURE() << "no exception";
  return {};
}

} // namespace geotandem::volume::testing
