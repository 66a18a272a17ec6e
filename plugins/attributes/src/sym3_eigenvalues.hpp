#pragma once
// Eigenvalues of a real symmetric 3x3 matrix in closed form (the trigonometric solution of the
// characteristic cubic), without calling a trigonometric function: cos(acos(r) / 3) comes from a
// polynomial (third_of_acos). Straight-line code (sqrt, divisions, min/max), so a loop over
// many matrices vectorises.
// Accuracy (tests/attributes/internals_test.cpp checks against Eigen and against the trigonometric
// formula): eigenvalues within about 1e-11 of the largest magnitude, except next to a repeated
// largest root, where r's own rounding limits any formula through r to about 1e-8; far below the
// float rounding of the tensor itself.

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace geotandem::attributes::detail {

// cos(phi) and sin(phi) for phi = acos(r) / 3, r in [-1, 1] (values outside are clamped).
// With s = sqrt((1 + r) / 2) = cos(acos(r) / 2), 1 - cos(phi) = k(s) (1 - s) where
// k(s) = (1 - cos(2/3 acos s)) / (1 - s) is analytic on [0, 1] (4/9 at s = 1): a polynomial
// in s gives it within 1e-12 relative. Working with 1 - cos(phi) keeps sin(phi) accurate where
// phi is near 0 (a repeated smallest eigenvalue: the planar case, the common one in seismic).
struct CosSin {
  double c, s;
};
inline CosSin third_of_acos(double r) {
  // k as a polynomial in x = 2 s - 1 on [-1, 1]: the Chebyshev interpolant of degree 12 at the
  // 13 Chebyshev nodes, rewritten in powers of x (the sum of the terms' magnitudes stays below 0.5,
  // so nothing cancels), evaluated by Estrin's scheme: a tree of depth 4 instead of a chain of 12
  // dependent steps, which kept the loop over many matrices waiting on latency.
  static constexpr double c[13] = {0.46791111376204425,     -0.026907018875910328,  0.004111357986966158,
                                   -0.0008213478572713075,  0.00018690180655774795, -4.594744703276468e-05,
                                   1.1890191672683579e-05,  -3.197249212733438e-06, 8.820344416558504e-07,
                                   -2.3861099626069165e-07, 6.824491221707902e-08,  -2.7736702507424457e-08,
                                   8.195423963395745e-09};
  const double rc = std::min(1.0, std::max(-1.0, r));
  const double s = std::sqrt(0.5 * (1.0 + rc));
  const double x = 2.0 * s - 1.0;
  const double x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
  const double p01 = c[0] + c[1] * x, p23 = c[2] + c[3] * x, p45 = c[4] + c[5] * x, p67 = c[6] + c[7] * x;
  const double p89 = c[8] + c[9] * x, p1011 = c[10] + c[11] * x;
  const double q0 = p01 + p23 * x2, q1 = p45 + p67 * x2, q2 = p89 + p1011 * x2;
  const double k_of_s = (q0 + q1 * x4) + (q2 + c[12] * x4) * x8;
  const double one_minus_c = k_of_s * (0.5 * (1.0 - rc) / (1.0 + s)); // 1 - s = ((1 - r) / 2) / (1 + s)
  return {1.0 - one_minus_c, std::sqrt(one_minus_c * (2.0 - one_minus_c))};
}

// Descending: l[0] >= l[1] >= l[2].
inline std::array<double, 3> sym3_eigenvalues(double a00, double a11, double a22, double a01, double a02, double a12) {
  const double q = (a00 + a11 + a22) * (1.0 / 3.0); // multiplied: a division is many times slower
  const double b00 = a00 - q, b11 = a11 - q, b22 = a22 - q;
  const double p2 = (b00 * b00 + b11 * b11 + b22 * b22 + 2.0 * (a01 * a01 + a02 * a02 + a12 * a12)) * (1.0 / 6.0);
  // p2 == 0 (a multiple of the identity): any r gives l1 = l2 = l3 = q, since p = 0.
  const bool round = p2 > 0.0;
  const double p = std::sqrt(round ? p2 : 1.0);
  // B = (A - qI) / p has eigenvalues 2 cos(phi + 2 pi m / 3) with cos(3 phi) = det(B) / 2.
  const double det = b00 * (b11 * b22 - a12 * a12) - a01 * (a01 * b22 - a12 * a02) + a02 * (a01 * a12 - b11 * a02);
  const double r = det / (2.0 * (round ? p2 : 1.0) * p);
  const auto [c, s] = third_of_acos(r); // cos(phi), sin(phi), phi in [0, pi/3]
  const double scale = round ? p : 0.0;
  // 2 cos(phi + 2 pi / 3) = -c - sqrt(3) s and 2 cos(phi - 2 pi / 3) = -c + sqrt(3) s.
  const double l1 = q + 2.0 * scale * c;
  const double l2 = q + scale * (std::numbers::sqrt3 * s - c);
  const double l3 = q - scale * (std::numbers::sqrt3 * s + c);
  return {l1, std::min(l1, std::max(l3, l2)), l3};
}

} // namespace geotandem::attributes::detail
