#pragma once
// Eigenvalues of a real symmetric 3x3 matrix in closed form (the trigonometric solution of the
// characteristic cubic). Only eigenvalues are needed for chaos, and this is several times faster
// than an iterative solver. Accuracy: absolute error about 1e-8 of the largest eigenvalue in the
// worst case (a repeated largest or smallest root, where acos is ill-conditioned), far below the
// float rounding of the tensor itself.

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace geotandem::attributes::detail {

// Descending: l[0] >= l[1] >= l[2].
inline std::array<double, 3> sym3_eigenvalues(double a00, double a11, double a22, double a01, double a02, double a12) {
  const double q = (a00 + a11 + a22) / 3.0;
  const double b00 = a00 - q, b11 = a11 - q, b22 = a22 - q;
  const double p2 = (b00 * b00 + b11 * b11 + b22 * b22 + 2.0 * (a01 * a01 + a02 * a02 + a12 * a12)) / 6.0;
  if (!(p2 > 0.0)) return {q, q, q};
  const double p = std::sqrt(p2);
  // B = (A - qI) / p has eigenvalues 2 cos(phi + 2 pi m / 3) with cos(3 phi) = det(B) / 2.
  const double det = b00 * (b11 * b22 - a12 * a12) - a01 * (a01 * b22 - a12 * a02) + a02 * (a01 * a12 - b11 * a02);
  const double r = std::clamp(det / (2.0 * p2 * p), -1.0, 1.0);
  const double c = std::cos(std::acos(r) / 3.0);     // phi = acos(r)/3 in [0, pi/3]: c in [1/2, 1]
  const double s = std::sqrt((1.0 - c) * (1.0 + c)); // sin(phi), without a second trigonometric call
  // 2 cos(phi + 2 pi / 3) = -c - sqrt(3) s and 2 cos(phi - 2 pi / 3) = -c + sqrt(3) s.
  const double l1 = q + 2.0 * p * c;
  const double l2 = q + p * (std::numbers::sqrt3 * s - c);
  const double l3 = q - p * (std::numbers::sqrt3 * s + c);
  return {l1, std::clamp(l2, l3, l1), l3};
}

} // namespace geotandem::attributes::detail
