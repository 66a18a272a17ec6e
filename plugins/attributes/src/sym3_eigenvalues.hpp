#pragma once
// Eigenvalues of a real symmetric 3x3 matrix in closed form (the trigonometric solution of the
// characteristic cubic), without calling a trigonometric function: cos(acos(r) / 3) comes from a
// Chebyshev series (third_of_acos). Straight-line code (sqrt, divisions, min/max), so a loop over
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
// k(s) = (1 - cos(2/3 acos s)) / (1 - s) is analytic on [0, 1] (4/9 at s = 1): a Chebyshev series
// in s gives it within 1e-12 relative. Working with 1 - cos(phi) keeps sin(phi) accurate where
// phi is near 0 (a repeated smallest eigenvalue: the planar case, the common one in seismic).
struct CosSin {
  double c, s;
};
inline CosSin third_of_acos(double r) {
  // Chebyshev coefficients of k on s in [0, 1] (x = 2 s - 1), degree 12, interpolating k at the
  // 13 Chebyshev nodes.
  static constexpr double a[13] = {0.4700408564425956,      -0.0275536253742923,    0.002155120474578135,
                                   -0.00022083187173241103, 2.580305752132904e-05,  -3.2594385364241692e-06,
                                   4.335740981712496e-07,   -5.983545108108228e-08, 8.487912859746526e-09,
                                   -1.2300270631098005e-09, 1.813109064595044e-10,  -2.7086623542406696e-11,
                                   4.001671857126829e-12};
  const double rc = std::min(1.0, std::max(-1.0, r));
  const double s = std::sqrt(0.5 * (1.0 + rc));
  const double x = 2.0 * s - 1.0;
  double b1 = 0.0, b2 = 0.0; // Clenshaw's recurrence
#pragma GCC unroll 12
  for (int k = 12; k >= 1; --k) {
    const double b = 2.0 * x * b1 - b2 + a[k];
    b2 = b1;
    b1 = b;
  }
  const double k_of_s = x * b1 - b2 + a[0];
  const double one_minus_c = k_of_s * (0.5 * (1.0 - rc) / (1.0 + s)); // 1 - s = ((1 - r) / 2) / (1 + s)
  return {1.0 - one_minus_c, std::sqrt(one_minus_c * (2.0 - one_minus_c))};
}

// Descending: l[0] >= l[1] >= l[2].
inline std::array<double, 3> sym3_eigenvalues(double a00, double a11, double a22, double a01, double a02, double a12) {
  const double q = (a00 + a11 + a22) / 3.0;
  const double b00 = a00 - q, b11 = a11 - q, b22 = a22 - q;
  const double p2 = (b00 * b00 + b11 * b11 + b22 * b22 + 2.0 * (a01 * a01 + a02 * a02 + a12 * a12)) / 6.0;
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
