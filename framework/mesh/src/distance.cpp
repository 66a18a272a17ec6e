// Sampled distances between surfaces (one-sided and symmetric Hausdorff).

#include <algorithm>
#include <cmath>
#include <string>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/quality.hpp"
#include "geotandem/mesh/vec.hpp"
#include "stars.hpp"
#include "triangle_grid.hpp"

namespace geotandem::mesh {

using namespace detail;

namespace {

// Barycentric sample k of a triangle: the centroid first, then a low-discrepancy sequence (the
// two-dimensional golden-ratio sequence) folded into the triangle. Deterministic, well spread.
Point triangle_sample(const Point& a, const Point& b, const Point& c, int k) {
  if (k == 0) return (1.0 / 3.0) * (a + b + c);
  constexpr double g1 = 0.7548776662466927, g2 = 0.5698402909980532; // 1/phi2, 1/phi2^2
  double u = std::fmod(0.5 + g1 * k, 1.0), v = std::fmod(0.5 + g2 * k, 1.0);
  if (u + v > 1.0) {
    u = 1.0 - u;
    v = 1.0 - v;
  }
  return a + u * (b - a) + v * (c - a);
}

struct Sums {
  double max2 = 0.0, sum2 = 0.0, sum = 0.0;
  std::size_t samples = 0;
  void add(double d2) {
    max2 = std::max(max2, d2);
    sum2 += d2;
    sum += std::sqrt(d2);
    ++samples;
  }
};

// The grid and the sums need finite coordinates; a NaN would silently poison the statistics.
void check_finite(const SurfaceMesh& s, const char* which) {
  for (const Triangle& t : s.triangles)
    for (std::uint32_t v : t)
      for (double x : s.points[v])
        if (!std::isfinite(x))
          throw DataError(std::string("the ") + which + " surface has a non-finite coordinate at vertex " +
                              std::to_string(v),
                          {}, "check the code or file that produced the surface");
}

Sums sample_distances(const SurfaceMesh& from, const SurfaceMesh& to, int samples_per_triangle) {
  if (samples_per_triangle < 0)
    throw InvalidArgument("samples_per_triangle is " + std::to_string(samples_per_triangle) +
                          "; it must be zero or positive");
  check_indices(from);
  check_indices(to);
  check_finite(from, "first");
  check_finite(to, "second");
  Sums sums;
  if (from.triangles.empty()) return sums;
  if (to.triangles.empty())
    throw InvalidArgument("cannot measure the distance to a surface without triangles", {},
                          "check that both surfaces were extracted");
  const TriangleGrid grid(to);
  auto scratch = grid.make_scratch();
  std::vector<bool> seen(from.points.size(), false);
  for (const Triangle& t : from.triangles)
    for (std::uint32_t v : t)
      if (!seen[v]) {
        seen[v] = true;
        sums.add(grid.nearest_distance2(from.points[v], scratch));
      }
  for (const Triangle& t : from.triangles)
    for (int k = 0; k < samples_per_triangle; ++k)
      sums.add(
          grid.nearest_distance2(triangle_sample(from.points[t[0]], from.points[t[1]], from.points[t[2]], k), scratch));
  return sums;
}

DistanceStats finish(const Sums& s) {
  DistanceStats stats;
  stats.samples = s.samples;
  if (s.samples == 0) return stats;
  const auto n = static_cast<double>(s.samples);
  stats.max = std::sqrt(s.max2);
  stats.rms = std::sqrt(s.sum2 / n);
  stats.mean = s.sum / n;
  return stats;
}

} // namespace

DistanceStats one_sided_distance(const SurfaceMesh& from, const SurfaceMesh& to, int samples_per_triangle) {
  return finish(sample_distances(from, to, samples_per_triangle));
}

DistanceStats hausdorff_distance(const SurfaceMesh& a, const SurfaceMesh& b, int samples_per_triangle) {
  const Sums ab = sample_distances(a, b, samples_per_triangle);
  const Sums ba = sample_distances(b, a, samples_per_triangle);
  Sums pooled;
  pooled.max2 = std::max(ab.max2, ba.max2);
  pooled.sum2 = ab.sum2 + ba.sum2;
  pooled.sum = ab.sum + ba.sum;
  pooled.samples = ab.samples + ba.samples;
  return finish(pooled);
}

} // namespace geotandem::mesh
