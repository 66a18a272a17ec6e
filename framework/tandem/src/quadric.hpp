#pragma once
// The two quadrics of the Attali cost (ALGORITHM.md, "Cost of a collapse"), stored compactly.
// Coordinates are index coordinates of the whole cube (voxel units).

#include <array>
#include <cmath>

#include "geotandem/mesh/vec.hpp"

namespace geotandem::tandem::detail {

using Vec3 = mesh::Point;
using mesh::operator+;
using mesh::operator-;
using mesh::operator*;
using mesh::cross;
using mesh::dot;
using mesh::norm;
using mesh::norm2;

// A symmetric 4x4 matrix as its upper triangle, row by row:
//   [0 xx, 1 xy, 2 xz, 3 xw,
//          4 yy, 5 yz, 6 yw,
//                7 zz, 8 zw,
//                      9 ww]
// x^T Q x for the homogeneous point x = (x, y, z, 1).
struct Quadric {
  std::array<double, 10> m{};

  // Adds w * p p^T with p = (n, d): w times the squared distance to the plane n.x + d = 0 (n unit).
  void add_plane(const Vec3& n, double d, double w) {
    m[0] += w * n[0] * n[0];
    m[1] += w * n[0] * n[1];
    m[2] += w * n[0] * n[2];
    m[3] += w * n[0] * d;
    m[4] += w * n[1] * n[1];
    m[5] += w * n[1] * n[2];
    m[6] += w * n[1] * d;
    m[7] += w * n[2] * n[2];
    m[8] += w * n[2] * d;
    m[9] += w * d * d;
  }
  Quadric& operator+=(const Quadric& o) {
    for (int i = 0; i < 10; ++i)
      m[i] += o.m[i];
    return *this;
  }
  friend Quadric operator+(Quadric a, const Quadric& b) { return a += b; }
  Quadric scaled(double s) const {
    Quadric q;
    for (int i = 0; i < 10; ++i)
      q.m[i] = s * m[i];
    return q;
  }
  double eval(const Vec3& p) const {
    const double x = p[0], y = p[1], z = p[2];
    return m[0] * x * x + 2.0 * m[1] * x * y + 2.0 * m[2] * x * z + 2.0 * m[3] * x + m[4] * y * y + 2.0 * m[5] * y * z +
           2.0 * m[6] * y + m[7] * z * z + 2.0 * m[8] * z + m[9];
  }
  // Entry (r, c) of the full symmetric matrix, r, c in 0..3.
  double at(int r, int c) const {
    static constexpr int kIndex[4][4] = {{0, 1, 2, 3}, {1, 4, 5, 6}, {2, 5, 7, 8}, {3, 6, 8, 9}};
    return m[kIndex[r][c]];
  }
};

// The isotropy term of one triangle t, kept as the five numbers that define
//   sum_t w_t (|x - t^|^2 + avg(t)) = A |x|^2 - 2 s.x + q,
// with A = sum w_t, s = sum w_t t^, q = sum w_t (t^.t^ + avg(t)). Sums of triangles add.
struct Isotropy {
  double area = 0.0;
  Vec3 s{0.0, 0.0, 0.0};
  double q = 0.0;

  static Isotropy of_triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
    return of_triangle(p0, p1, p2, cross(p1 - p0, p2 - p0));
  }
  // With the triangle's (p1 - p0) x (p2 - p0) already at hand.
  static Isotropy of_triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& n) {
    Isotropy t;
    const double w = 0.5 * norm(n);
    const Vec3 centre = (1.0 / 3.0) * (p0 + p1 + p2);
    const double avg = (norm2(p0 - centre) + norm2(p1 - centre) + norm2(p2 - centre)) / 12.0;
    t.area = w;
    t.s = w * centre;
    t.q = w * (dot(centre, centre) + avg);
    return t;
  }
  Isotropy& operator+=(const Isotropy& o) {
    area += o.area;
    s = s + o.s;
    q += o.q;
    return *this;
  }
  Isotropy& operator-=(const Isotropy& o) {
    area -= o.area;
    s = s - o.s;
    q -= o.q;
    return *this;
  }
  // As a quadric (upper-left block area * I, last column -s, corner q).
  Quadric as_quadric() const {
    Quadric g;
    g.m = {area, 0.0, 0.0, -s[0], area, 0.0, -s[1], area, -s[2], q};
    return g;
  }
};

} // namespace geotandem::tandem::detail
