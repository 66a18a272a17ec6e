// Triangle shape (seed section 4), area and enclosed volume.

#include "geotandem/mesh/quality.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geotandem/mesh/vec.hpp"
#include "stars.hpp"

namespace geotandem::mesh {

using namespace detail;

double aspect_ratio(const Point& a, const Point& b, const Point& c) {
  // M_t = 1/3 sum (v - t^)(v - t^)^T lives in the triangle's plane. Its determinant there is
  // lambda1 * lambda2 = |u x w|^2 / 27 (u = b - a, w = c - a), exact for slivers; lambda1 comes
  // from the 2 x 2 matrix in an orthonormal frame of the plane, exact for near-equilateral
  // triangles (the trace-and-determinant formula would lose half the digits there).
  const Point u = b - a, w = c - a;
  const Point n = cross(u, w);
  const double n2 = norm2(n);
  if (!(n2 > 0.0)) return 0.0; // collinear or a point
  const Point e1 = (1.0 / norm(u)) * u;
  const Point e2 = (1.0 / std::sqrt(n2)) * cross(n, e1);
  const Point g = (1.0 / 3.0) * (a + b + c);
  double xx = 0.0, yy = 0.0, xy = 0.0;
  for (const Point* v : {&a, &b, &c}) {
    const Point d = *v - g;
    const double x = dot(d, e1), y = dot(d, e2);
    xx += x * x;
    yy += y * y;
    xy += x * y;
  }
  const double lambda1 = (0.5 * (xx + yy) + std::hypot(0.5 * (xx - yy), xy)) / 3.0;
  const double lambda2 = n2 / 27.0 / lambda1;
  return std::clamp(std::sqrt(lambda2 / lambda1), 0.0, 1.0);
}

double anisotropy(const SurfaceMesh& surface) {
  if (surface.triangles.empty()) return 0.0;
  check_indices(surface);
  double sum = 0.0;
  for (const Triangle& t : surface.triangles)
    sum += aspect_ratio(surface.points[t[0]], surface.points[t[1]], surface.points[t[2]]);
  return 1.0 - sum / static_cast<double>(surface.triangles.size());
}

double small_angle_share(const SurfaceMesh& surface, double degrees) {
  if (surface.triangles.empty()) return 0.0;
  check_indices(surface);
  const double limit = degrees * std::numbers::pi / 180.0;
  std::size_t small = 0;
  for (const Triangle& t : surface.triangles) {
    const Point& a = surface.points[t[0]];
    const Point& b = surface.points[t[1]];
    const Point& c = surface.points[t[2]];
    // atan2(|u x w|, u . w) keeps its precision for angles near 0 and pi, where acos does not.
    auto angle = [](const Point& u, const Point& w) { return std::atan2(norm(cross(u, w)), dot(u, w)); };
    const double smallest = std::min({angle(b - a, c - a), angle(c - b, a - b), angle(a - c, b - c)});
    if (smallest < limit) ++small;
  }
  return static_cast<double>(small) / static_cast<double>(surface.triangles.size());
}

double surface_area(const SurfaceMesh& surface) {
  check_indices(surface);
  double twice = 0.0;
  for (const Triangle& t : surface.triangles) {
    const Point& a = surface.points[t[0]];
    twice += norm(cross(surface.points[t[1]] - a, surface.points[t[2]] - a));
  }
  return 0.5 * twice;
}

double enclosed_volume(const SurfaceMesh& surface) {
  if (surface.triangles.empty()) return 0.0;
  check_indices(surface);
  // Tetrahedra from a point of the surface rather than the origin: the sum is the same for a
  // closed surface, and world coordinates of 10^6 m lose no digits.
  const Point origin = surface.points[surface.triangles.front()[0]];
  double six = 0.0;
  for (const Triangle& t : surface.triangles)
    six += dot(surface.points[t[0]] - origin, cross(surface.points[t[1]] - origin, surface.points[t[2]] - origin));
  return six / 6.0;
}

} // namespace geotandem::mesh
