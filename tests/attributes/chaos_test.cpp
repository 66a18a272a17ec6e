#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <limits>

#include "fixtures.hpp"
#include "geotandem/attributes/chaos.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::attributes {
namespace {

using testing::cube;
using testing::noise;
using testing::reflect;

TEST(Chaos, HaloIsTheSumOfTheTruncationRadii) {
  auto u = cube({4, 4, 16}, [](int, int, int k) { return k; });
  EXPECT_EQ(Chaos(u).halo(), (Index3{9, 9, 12}));
  EXPECT_EQ(Chaos(u, {.sigma_g = 0.5, .sigma_t_across = 1.0, .sigma_t_along = 1.5}).halo(), (Index3{5, 5, 7}));
}

TEST(Chaos, BoxAloneEqualsWholeCube) {
  auto u = cube({24, 20, 64}, [](int i, int j, int k) { return std::cos(0.4 * k + 0.1 * i) + 0.7 * noise(i, j, k); });
  testing::expect_boxes_match_whole(Chaos(u));
  testing::expect_boxes_match_whole(Chaos(u, {.formula = ChaosFormula::marfurt, .sigma_g = 1.5, .sigma_t_along = 2}));
}

TEST(Chaos, BoxAloneEqualsWholeCubeWhenTheHaloIsWiderThanTheCube) {
  auto u = cube({4, 3, 10}, [](int i, int j, int k) { return noise(i, j, k, 4); });
  Chaos chaos(u);
  const Box bounds = u->geometry().bounds();
  const std::vector<float> whole = chaos.read(bounds);
  for (const Box& box : {Box{{0, 0, 0}, {1, 1, 1}}, Box{{1, 1, 3}, {4, 3, 10}}, Box{{2, 0, 0}, {3, 3, 7}}}) {
    const std::vector<float> part = chaos.read(box);
    for (auto i = box.lo[0]; i < box.hi[0]; ++i)
      for (auto j = box.lo[1]; j < box.hi[1]; ++j)
        for (auto k = box.lo[2]; k < box.hi[2]; ++k)
          ASSERT_EQ(part[box.offset({i, j, k})], whole[bounds.offset({i, j, k})]) << box.to_string();
  }
}

TEST(Chaos, FlatReflectorsGiveZero) {
  // The gradient points along the trace everywhere (the mirror keeps the layers flat): T has rank 1.
  auto u = cube({24, 20, 64}, [](int, int, int k) { return std::cos(0.4 * k); });
  for (ChaosFormula formula : {ChaosFormula::planarity, ChaosFormula::marfurt})
    for (float v : Chaos(u, {.formula = formula}).read(u->geometry().bounds()))
      ASSERT_LT(std::abs(v), 1e-5f);
}

TEST(Chaos, DippingPlaneWaveGivesZeroInside) {
  // Separable filters map a plane wave cos(w.x) to sin(w.x) times a fixed vector: T has rank 1 wherever
  // the halo stays inside the cube (the mirror bends the layers at the faces).
  const Index3 shape{24, 22, 64};
  auto u = cube(shape, [](int i, int j, int k) { return std::cos(0.35 * k + 0.2 * i - 0.15 * j); });
  Chaos chaos(u);
  const Box inside{{9, 9, 12}, {15, 13, 52}};
  for (float v : chaos.read(inside))
    ASSERT_LT(v, 1e-3f);
}

TEST(Chaos, IsotropicNoiseGivesHighChaos) {
  auto u = cube({24, 20, 64}, [](int i, int j, int k) { return noise(i, j, k, 9); });
  auto mean_and_range = [&](ChaosFormula formula, double top) {
    const std::vector<float> c = Chaos(u, {.formula = formula}).read(u->geometry().bounds());
    double mean = 0.0;
    for (float v : c) {
      EXPECT_GE(v, 0.0f);
      EXPECT_LE(v, top);
      mean += v;
    }
    return mean / static_cast<double>(c.size());
  };
  EXPECT_GT(mean_and_range(ChaosFormula::planarity, 1.0), 0.75);
  const double marfurt = mean_and_range(ChaosFormula::marfurt, 2.0);
  EXPECT_GT(marfurt, 0.75);
  EXPECT_LT(marfurt, 1.25);
}

// Gaussian and derivative taps written out from the definitions (radius ceil(3 sigma)).
std::vector<double> gaussian(double sigma, bool derivative) {
  const int r = std::max(1, static_cast<int>(std::ceil(3 * sigma)));
  std::vector<double> w;
  double norm = 0.0;
  for (int t = -r; t <= r; ++t) {
    const double g = std::exp(-t * t / (2 * sigma * sigma));
    w.push_back(derivative ? t * g : g);
    norm += derivative ? t * t * g : g;
  }
  for (double& v : w)
    v /= norm;
  return w;
}

TEST(Chaos, MatchesADirectThreeDimensionalComputation) {
  // Non-separable sums in double over the mirrored cube, then Eigen's solver. The cube is smaller
  // than the halo on two axes, so repeated reflections are covered too.
  const Index3 shape{8, 7, 16};
  auto field = [](int i, int j, int k) { return noise(i, j, k, 6) + std::cos(0.5 * k + 0.3 * i); };
  auto u = cube(shape, field);
  const ChaosOptions options{};
  const std::vector<float> chaos = Chaos(u, options).read(u->geometry().bounds());

  const std::vector<double> g = gaussian(options.sigma_g, false), d = gaussian(options.sigma_g, true);
  const std::vector<double> ta = gaussian(options.sigma_t_across, false), tk = gaussian(options.sigma_t_along, false);
  const int rg = static_cast<int>(g.size() / 2), ra = static_cast<int>(ta.size() / 2),
            rk = static_cast<int>(tk.size() / 2);
  auto at = [](const std::vector<double>& w, int t) { return w[static_cast<std::size_t>(t)]; };
  // The mirrored input on the cube grown by both radii, then the gradient on the cube grown by the
  // tensor's radii (plain loops: Eigen unoptimised is too slow for the sanitizer build).
  const int pi = 8 + 2 * (ra + rg), pj = 7 + 2 * (ra + rg), pk = 16 + 2 * (rk + rg);
  std::vector<double> padded(static_cast<std::size_t>(pi * pj * pk));
  for (int i = 0; i < pi; ++i)
    for (int j = 0; j < pj; ++j)
      for (int k = 0; k < pk; ++k)
        padded[static_cast<std::size_t>((i * pj + j) * pk + k)] =
            field(reflect(i - ra - rg, 8), reflect(j - ra - rg, 7), reflect(k - rk - rg, 16));
  const int ni = 8 + 2 * ra, nj = 7 + 2 * ra, nk = 16 + 2 * rk;
  std::vector<std::array<double, 3>> grad(static_cast<std::size_t>(ni * nj * nk));
  for (int i = 0; i < ni; ++i)
    for (int j = 0; j < nj; ++j)
      for (int k = 0; k < nk; ++k) {
        std::array<double, 3> s{0, 0, 0};
        for (int a = 0; a <= 2 * rg; ++a)
          for (int b = 0; b <= 2 * rg; ++b)
            for (int c = 0; c <= 2 * rg; ++c) {
              const double v = padded[static_cast<std::size_t>(((i + a) * pj + (j + b)) * pk + (k + c))];
              s[0] += v * at(d, a) * at(g, b) * at(g, c);
              s[1] += v * at(g, a) * at(d, b) * at(g, c);
              s[2] += v * at(g, a) * at(g, b) * at(d, c);
            }
        grad[static_cast<std::size_t>((i * nj + j) * nk + k)] = s;
      }
  double worst = 0.0;
  std::size_t n = 0;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 7; ++j)
      for (int k = 0; k < 16; ++k, ++n) {
        double t[3][3] = {};
        for (int a = 0; a <= 2 * ra; ++a)
          for (int b = 0; b <= 2 * ra; ++b)
            for (int c = 0; c <= 2 * rk; ++c) {
              const auto& v = grad[static_cast<std::size_t>(((i + a) * nj + (j + b)) * nk + (k + c))];
              const double w = at(ta, a) * at(ta, b) * at(tk, c);
              for (int r = 0; r < 3; ++r)
                for (int q = 0; q < 3; ++q)
                  t[r][q] += w * v[static_cast<std::size_t>(r)] * v[static_cast<std::size_t>(q)];
            }
        Eigen::Matrix3d m;
        for (int r = 0; r < 3; ++r)
          for (int q = 0; q < 3; ++q)
            m(r, q) = t[r][q];
        const Eigen::Vector3d l =
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m, Eigen::EigenvaluesOnly).eigenvalues();
        const double expected = 2 * l(1) / (l(2) + l(1));
        worst = std::max(worst, std::abs(chaos[n] - expected));
        ASSERT_NEAR(chaos[n], expected, 1e-4) << i << ", " << j << ", " << k;
      }
  EXPECT_LT(worst, 1e-5); // float filters against double sums: observed below 1e-6
}

TEST(Chaos, RejectsBadSigmasNamingThemAndTheirRange) {
  auto u = cube({4, 4, 16}, [](int, int, int k) { return k; });
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (auto [options, name] :
       {std::pair{ChaosOptions{.sigma_g = -1}, "'sigma_g'"}, std::pair{ChaosOptions{.sigma_g = 0}, "'sigma_g'"},
        std::pair{ChaosOptions{.sigma_t_across = 25}, "'sigma_t_across'"},
        std::pair{ChaosOptions{.sigma_t_along = nan}, "'sigma_t_along'"}}) {
    try {
      Chaos c(u, options);
      FAIL() << name << " accepted";
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("(0, 20]"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(Chaos(u, {.formula = static_cast<ChaosFormula>(7)}), InvalidArgument);
}

} // namespace
} // namespace geotandem::attributes
