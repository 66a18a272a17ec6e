// The machinery under every attribute: mirror padding, filter kernels and passes, and the closed-form
// eigenvalues, each against an independent computation.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "array3.hpp"
#include "filters.hpp"
#include "fixtures.hpp"
#include "mirror.hpp"
#include "sym3_eigenvalues.hpp"

namespace geotandem::attributes {
namespace {

using testing::cube;
using testing::noise;
using testing::reflect;
using volume::Box;
using volume::Index3;

TEST(Mirror, IndexMatchesRepeatedReflection) {
  for (int n : {1, 2, 3, 7})
    for (int m = -40; m < 40; ++m)
      EXPECT_EQ(detail::mirror_index(m, n), reflect(m, n)) << "m " << m << " n " << n;
}

TEST(Mirror, PaddedReadEqualsReflectedCube) {
  const Index3 shape{5, 4, 9};
  auto u = cube(shape, [](int i, int j, int k) { return 100.0 * i + 10.0 * j + k; });
  // Halos wider than the cube on two axes force repeated reflections.
  for (const Box& box : {Box{{0, 0, 0}, {2, 3, 4}}, Box{{1, 1, 2}, {5, 4, 9}}, Box{{0, 0, 0}, shape}}) {
    const Index3 halo{7, 2, 5};
    const detail::Array3 padded = detail::read_mirrored(*u, box, halo);
    const Box grown = box.grown(halo);
    ASSERT_EQ(padded.shape, grown.shape());
    std::size_t n = 0;
    for (auto i = grown.lo[0]; i < grown.hi[0]; ++i)
      for (auto j = grown.lo[1]; j < grown.hi[1]; ++j)
        for (auto k = grown.lo[2]; k < grown.hi[2]; ++k, ++n) {
          const double expected = 100.0 * reflect(static_cast<int>(i), 5) + 10.0 * reflect(static_cast<int>(j), 4) +
                                  reflect(static_cast<int>(k), 9);
          ASSERT_EQ(padded.data[n], expected) << "at " << i << ", " << j << ", " << k << " of " << box.to_string();
        }
  }
}

// Large arrays reuse the storage that earlier ones of the thread freed (array3.hpp): a padded read
// into reused storage must still write every sample, at the cube's faces too.
TEST(Mirror, PaddedReadsIntoReusedStorageHoldNothingOfTheLastRead) {
  const Index3 shape{60, 100, 100};
  const Box box{{0, 30, 50}, {60, 100, 100}}; // on five faces: the mirrored path
  const Index3 halo{4, 6, 8};
  const auto expected_at = [](double seed, std::int64_t i, std::int64_t j, std::int64_t k) {
    return seed + 100.0 * reflect(static_cast<int>(i), 60) + 10.0 * reflect(static_cast<int>(j), 100) +
           0.5 * reflect(static_cast<int>(k), 100);
  };
  detail::release_spare_arrays();
  const float* first_storage = nullptr;
  for (double seed : {1000.0, -5000.0}) {
    auto u = cube(shape, [&](int i, int j, int k) { return expected_at(seed, i, j, k); });
    const detail::Array3 padded = detail::read_mirrored(*u, box, halo);
    ASSERT_GE(padded.count(), detail::kReusedFloats);
    if (first_storage) {
      EXPECT_EQ(padded.data.get(), first_storage) << "the second read should reuse the first's";
    }
    first_storage = padded.data.get();
    const Box grown = box.grown(halo);
    std::size_t n = 0;
    for (auto i = grown.lo[0]; i < grown.hi[0]; ++i)
      for (auto j = grown.lo[1]; j < grown.hi[1]; ++j)
        for (auto k = grown.lo[2]; k < grown.hi[2]; ++k, ++n)
          ASSERT_EQ(padded.data[n], static_cast<float>(expected_at(seed, i, j, k)))
              << "at " << i << ", " << j << ", " << k;
  }
}

TEST(ArrayStorage, KeepsAFewLargeSparesAndNeverTheSmallOnes) {
  detail::release_spare_arrays();
  EXPECT_EQ(detail::spare_array_bytes(), 0u);
  { const detail::Array3 small({10, 10, 10}); }
  EXPECT_EQ(detail::spare_array_bytes(), 0u) << "a small array went to the spares";

  const float* kept = nullptr;
  {
    const detail::Array3 large({64, 64, 80});
    kept = large.data.get();
  }
  EXPECT_EQ(detail::spare_array_bytes(), 64 * 64 * 80 * sizeof(float));
  { // at most twice the size asked: a spare far larger is not handed out for a small request
    const detail::Array3 half({64, 64, 39});
    EXPECT_NE(half.data.get(), kept);
  }
  {
    const detail::Array3 same({80, 64, 64});
    EXPECT_EQ(same.data.get(), kept);
  }
  // However many are freed, a thread keeps a bounded number, the largest ones.
  detail::release_spare_arrays();
  {
    std::vector<detail::Array3> many;
    for (std::int64_t n = 64; n < 64 + 12; ++n)
      many.emplace_back(Index3{n, 64, 64});
  }
  const std::size_t largest_three = (73 + 74 + 75) * 64 * 64 * sizeof(float);
  EXPECT_EQ(detail::spare_array_bytes(), largest_three);
}

// Reconstructs the full tap array w(-r..r) from a kernel's half.
std::vector<double> full_taps(const detail::Kernel& kernel) {
  const int r = kernel.radius();
  std::vector<double> w(static_cast<std::size_t>(2 * r + 1));
  for (int t = -r; t <= r; ++t) {
    const double h = kernel.half[static_cast<std::size_t>(std::abs(t))];
    w[static_cast<std::size_t>(t + r)] = (t < 0 && kernel.symmetry == detail::Symmetry::odd) ? -h : h;
  }
  return w;
}

TEST(Kernels, GaussianHasUnitSumAndDocumentedRadius) {
  for (double sigma : {0.2, 1.0, 2.0, 3.0, 4.5}) {
    const detail::Kernel g = detail::gaussian_kernel(sigma);
    EXPECT_EQ(g.radius(), std::max(1, static_cast<int>(std::ceil(3.0 * sigma))));
    double sum = 0.0;
    for (double w : full_taps(g))
      sum += w;
    EXPECT_NEAR(sum, 1.0, 1e-6);
    for (int t = 1; t <= g.radius(); ++t)
      EXPECT_LT(g.half[static_cast<std::size_t>(t)], g.half[t - 1u]);
  }
}

TEST(Kernels, DerivativeIsExactOnRamps) {
  for (double sigma : {0.5, 1.0, 2.5}) {
    const detail::Kernel d = detail::gaussian_derivative_kernel(sigma);
    const std::vector<double> w = full_taps(d);
    double sum = 0.0, moment = 0.0;
    for (int t = -d.radius(); t <= d.radius(); ++t) {
      sum += w[static_cast<std::size_t>(t + d.radius())];
      moment += t * w[static_cast<std::size_t>(t + d.radius())];
    }
    EXPECT_NEAR(sum, 0.0, 1e-7);
    EXPECT_NEAR(moment, 1.0, 1e-6);
  }
}

// The transformer's gain at f cycles per sample: the response of the odd kernel to sin(2 pi f t).
double hilbert_gain(const detail::Kernel& h, double f) {
  double gain = 0.0;
  for (int t = 1; t <= h.radius(); ++t)
    gain -= 2.0 * h.half[static_cast<std::size_t>(t)] * std::sin(2 * std::numbers::pi * f * t);
  return gain;
}

TEST(Kernels, HilbertGainIsFlatInTheDocumentedBand) {
  const detail::Kernel h = detail::hilbert_kernel(32);
  EXPECT_EQ(h.symmetry, detail::Symmetry::odd);
  for (int t = 0; t <= 32; t += 2)
    EXPECT_EQ(h.half[static_cast<std::size_t>(t)], 0.0f);
  for (double f = 0.05; f <= 0.45; f += 0.005)
    EXPECT_NEAR(hilbert_gain(h, f), 1.0, 4e-4) << "f " << f;
  // A shorter transformer keeps the same band only roughly: the gain still rises towards 1.
  EXPECT_LT(std::abs(hilbert_gain(detail::hilbert_kernel(16), 0.25) - 1.0), 0.01);
}

TEST(Filters, CorrelateMatchesDirectSumOnEveryAxis) {
  const Index3 shape{9, 8, 11};
  auto u = cube(shape, [](int i, int j, int k) { return noise(i, j, k); });
  detail::Array3 in = detail::read_mirrored(*u, u->geometry().bounds(), {0, 0, 0});
  for (const detail::Kernel& kernel : {detail::gaussian_kernel(1.0), detail::gaussian_derivative_kernel(0.9)})
    for (int axis = 0; axis < 3; ++axis) {
      const detail::Array3 out = detail::correlate(in, axis, kernel);
      const int r = kernel.radius();
      const std::vector<double> w = full_taps(kernel);
      Index3 expected_shape = shape;
      expected_shape[axis] -= 2 * r;
      ASSERT_EQ(out.shape, expected_shape);
      std::size_t n = 0;
      for (int i = 0; i < out.shape[0]; ++i)
        for (int j = 0; j < out.shape[1]; ++j)
          for (int k = 0; k < out.shape[2]; ++k, ++n) {
            double sum = 0.0;
            for (int t = -r; t <= r; ++t) {
              int at[3] = {i, j, k};
              at[axis] += r + t;
              sum += w[static_cast<std::size_t>(t + r)] * noise(at[0], at[1], at[2]);
            }
            ASSERT_NEAR(out.data[n], sum, 1e-5) << "axis " << axis << " at " << i << ", " << j << ", " << k;
          }
    }
}

// One output of a filter in the order every path must keep (w0 c, then w_t (plus_t +- minus_t) for
// t = 1 .. radius, zero taps skipped), in floats: the vector blocks, the lines rounded up to whole
// vectors and the batches of planes across must all give exactly these bits.
float sum_in_order(const detail::Kernel& kernel, const std::function<float(int)>& at) {
  const bool even = kernel.symmetry == detail::Symmetry::even;
  float sum = even ? kernel.half[0] * at(0) : 0.0f;
  for (int t = 1; t <= kernel.radius(); ++t) {
    const float w = kernel.half[static_cast<std::size_t>(t)];
    if (w == 0.0f) continue;
    sum += w * (even ? at(t) + at(-t) : at(t) - at(-t));
  }
  return sum;
}

std::vector<detail::Kernel> kernels_of_every_path() {
  // Radii 1-6 and 9 have their own loop, 7 and 20 the general one, the Hilbert kernel (zero taps)
  // the general one with skips.
  std::vector<detail::Kernel> kernels;
  for (double sigma : {0.3, 0.6, 1.0, 1.3, 1.6, 2.0, 2.3, 3.0, 6.7})
    kernels.push_back(detail::gaussian_kernel(sigma));
  kernels.push_back(detail::gaussian_derivative_kernel(1.0));
  kernels.push_back(detail::gaussian_derivative_kernel(2.3));
  kernels.push_back(detail::hilbert_kernel(8));
  return kernels;
}

TEST(Filters, EveryLineLengthGivesTheBitsOfOneSumAtATime) {
  // Lines of 1 to 45 outputs along the trace, 1 to 3 lines per plane: lines rounded up to whole
  // vectors overlap their successor's first outputs, and the last lines of the array cannot.
  for (const detail::Kernel& kernel : kernels_of_every_path())
    for (int outputs = 1; outputs <= 45; outputs += outputs < 12 ? 1 : 11)
      for (int lines = 1; lines <= 3; ++lines) {
        const int r = kernel.radius();
        const Index3 shape{2, lines, outputs + 2 * r};
        auto u = cube(shape, [](int i, int j, int k) { return noise(i, j, k); });
        const detail::Array3 in = detail::read_mirrored(*u, u->geometry().bounds(), {0, 0, 0});
        const detail::Array3 out = detail::correlate(in, 2, kernel);
        ASSERT_EQ(out.shape, (Index3{2, lines, outputs}));
        std::size_t n = 0;
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < lines; ++j)
            for (int k = 0; k < outputs; ++k, ++n) {
              const float expected = sum_in_order(kernel, [&](int t) {
                return in.data[static_cast<std::size_t>((i * lines + j) * shape[2] + k + r + t)];
              });
              ASSERT_EQ(out.data[n], expected) << "radius " << r << ", " << outputs << " outputs, line " << j;
            }
      }
}

TEST(Filters, PlanesFilteredTogetherGiveTheBitsOfOneSumAtATime) {
  // 1 to 6 output planes at once, of sizes that leave blocks of 32, of 8 and single outputs.
  for (const detail::Kernel& kernel : kernels_of_every_path())
    for (int count = 1; count <= 6; ++count)
      for (std::size_t n : {std::size_t{1}, std::size_t{13}, std::size_t{77}}) {
        const int r = kernel.radius();
        std::vector<std::vector<float>> planes(static_cast<std::size_t>(2 * r + count), std::vector<float>(n));
        for (std::size_t p = 0; p < planes.size(); ++p)
          for (std::size_t m = 0; m < n; ++m)
            planes[p][m] = static_cast<float>(noise(static_cast<int>(p), static_cast<int>(m), 3));
        std::vector<const float*> in;
        for (const auto& plane : planes)
          in.push_back(plane.data());
        std::vector<std::vector<float>> out(static_cast<std::size_t>(count), std::vector<float>(n));
        std::vector<float*> outs;
        for (auto& plane : out)
          outs.push_back(plane.data());
        detail::correlate_planes(in.data(), kernel, outs.data(), n, count);
        for (int b = 0; b < count; ++b)
          for (std::size_t m = 0; m < n; ++m) {
            const float expected =
                sum_in_order(kernel, [&](int t) { return planes[static_cast<std::size_t>(b + r + t)][m]; });
            ASSERT_EQ(out[static_cast<std::size_t>(b)][m], expected)
                << "radius " << r << ", plane " << b << " of " << count << ", sample " << m << " of " << n;
          }
      }
}

TEST(Eigenvalues, MatchEigenOnRandomAndDegenerateMatrices) {
  std::vector<Eigen::Matrix3d> cases;
  for (int c = 0; c < 200; ++c) {
    Eigen::Matrix3d g;
    for (int r = 0; r < 3; ++r)
      for (int s = 0; s < 3; ++s)
        g(r, s) = noise(c, r, s, 7);
    cases.push_back(g * g.transpose()); // positive semi-definite, like a structure tensor
  }
  Eigen::Vector3d v(0.3, -0.5, 0.8);
  cases.push_back(v * v.transpose());                 // rank one: planar
  cases.push_back(Eigen::Matrix3d::Identity() * 2.5); // isotropic
  cases.push_back(Eigen::Vector3d(4, 4, 1).asDiagonal());
  cases.push_back(Eigen::Vector3d(4, 1, 1).asDiagonal());
  cases.push_back(Eigen::Matrix3d::Zero());
  for (const Eigen::Matrix3d& a : cases) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(a, Eigen::EigenvaluesOnly);
    const Eigen::Vector3d ascending = solver.eigenvalues();
    const auto l = detail::sym3_eigenvalues(a(0, 0), a(1, 1), a(2, 2), a(0, 1), a(0, 2), a(1, 2));
    const double scale = std::max(1.0, std::abs(ascending(2)));
    EXPECT_NEAR(l[0], ascending(2), 1e-7 * scale);
    EXPECT_NEAR(l[1], ascending(1), 1e-7 * scale);
    EXPECT_NEAR(l[2], ascending(0), 1e-7 * scale);
    EXPECT_GE(l[0], l[1]);
    EXPECT_GE(l[1], l[2]);
  }
}

// The series replacing cos(acos(r)/3) and its sine, against the trigonometric functions, on a fine
// grid and at the ends (r = 1: a repeated smallest eigenvalue, where sin must stay accurate).
TEST(Eigenvalues, ThirdOfAcosMatchesTrigonometry) {
  for (int n = 0; n <= 200000; ++n) {
    const double r = -1.0 + n / 100000.0;
    const double phi = std::acos(std::clamp(r, -1.0, 1.0)) / 3.0;
    const detail::CosSin cs = detail::third_of_acos(r);
    ASSERT_NEAR(cs.c, std::cos(phi), 2e-12) << "r = " << r;
    ASSERT_NEAR(cs.s, std::sin(phi), 2e-12 + 1e-9 * std::sin(phi)) << "r = " << r;
  }
  for (double r : {1.0, 1.0 - 1e-15, 1.0 - 1e-12, 1.0 - 1e-9}) {
    const double phi = std::acos(r) / 3.0;
    EXPECT_NEAR(detail::third_of_acos(r).s, std::sin(phi), 1e-9 * std::sin(phi) + 1e-300) << "r = " << r;
  }
  EXPECT_EQ(detail::third_of_acos(1.0).s, 0.0);
  EXPECT_EQ(detail::third_of_acos(1.5).c, 1.0);
}

// Planar tensors (l1 >> l2 = l3): the common case in seismic, where chaos is small. A repeated root
// makes r = 1 - O(rounding), and any formula through r then errs by about sqrt(1e-16) of l1 on the
// repeated pair (the trigonometric one as well): 2e-8 here, below a float's resolution of l1.
TEST(Eigenvalues, PlanarTensorsAreAccurate) {
  for (int c = 0; c < 100; ++c) {
    Eigen::Vector3d n(noise(c, 1, 2, 3), noise(c, 4, 5, 6), 1.0 + noise(c, 7, 8, 9));
    n.normalize();
    const double weak = std::pow(10.0, -1.0 - c % 6); // l2 = l3 = weak, l1 = 1 + weak
    const Eigen::Matrix3d a = n * n.transpose() + weak * Eigen::Matrix3d::Identity();
    const auto l = detail::sym3_eigenvalues(a(0, 0), a(1, 1), a(2, 2), a(0, 1), a(0, 2), a(1, 2));
    EXPECT_NEAR(l[0], 1.0 + weak, 1e-12);
    EXPECT_NEAR(l[1], weak, 2e-8) << "weak = " << weak;
    EXPECT_NEAR(l[2], weak, 2e-8) << "weak = " << weak;
  }
}

} // namespace
} // namespace geotandem::attributes
