#pragma once
// The vector operations on Point (std::array<double, 3>) that the measures and the collapse loop
// share. A caller outside namespace geotandem::mesh brings in the operators with a using-declaration
// (std::array is found in std only).

#include <cmath>

#include "surface.hpp"

namespace geotandem::mesh {

inline Point operator+(const Point& a, const Point& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Point operator-(const Point& a, const Point& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Point operator*(double s, const Point& a) {
  return {s * a[0], s * a[1], s * a[2]};
}
inline double dot(const Point& a, const Point& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Point cross(const Point& a, const Point& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm2(const Point& a) {
  return dot(a, a);
}
inline double norm(const Point& a) {
  return std::sqrt(dot(a, a));
}

} // namespace geotandem::mesh
