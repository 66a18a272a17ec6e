#include "triangle_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geotandem/mesh/vec.hpp"

namespace geotandem::mesh::detail {

namespace {

double point_segment_distance2(const Point& p, const Point& a, const Point& b) {
  const Point ab = b - a, ap = p - a;
  const double len2 = norm2(ab);
  const double t = len2 > 0.0 ? std::clamp(dot(ap, ab) / len2, 0.0, 1.0) : 0.0;
  return norm2(ap - t * ab);
}

// Grids larger than this many cells per triangle cost more memory than they save time.
constexpr double max_cells_per_triangle = 4.0;

} // namespace

double point_triangle_distance2(const Point& p, const Point& a, const Point& b, const Point& c) {
  const Point n = cross(b - a, c - a);
  const double nn = norm2(n);
  if (!(nn > 0.0)) // collinear or a point: the nearest point is on the border
    return std::min(
        {point_segment_distance2(p, a, b), point_segment_distance2(p, b, c), point_segment_distance2(p, c, a)});
  // The projection q of p on the plane is inside when it is on the inner side of all three edges;
  // then the distance is the height above the plane. Otherwise the nearest point lies on an edge
  // that q is outside of (an edge q is inside of would have points of the triangle nearer to q).
  const double height = dot(p - a, n);
  const Point q = p - (height / nn) * n;
  const bool out_ab = dot(cross(b - a, q - a), n) < 0.0;
  const bool out_bc = dot(cross(c - b, q - b), n) < 0.0;
  const bool out_ca = dot(cross(a - c, q - c), n) < 0.0;
  if (!out_ab && !out_bc && !out_ca) return height * height / nn;
  double best = std::numeric_limits<double>::infinity();
  if (out_ab) best = point_segment_distance2(p, a, b);
  if (out_bc) best = std::min(best, point_segment_distance2(p, b, c));
  if (out_ca) best = std::min(best, point_segment_distance2(p, c, a));
  return best;
}

TriangleGrid::TriangleGrid(const SurfaceMesh& surface) : surface_(&surface) {
  const auto& pts = surface.points;
  Point lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  Point hi{-lo[0], -lo[1], -lo[2]};
  double edge_sum = 0.0;
  for (const Triangle& t : surface.triangles) {
    for (std::uint32_t v : t)
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], pts[v][a]);
        hi[a] = std::max(hi[a], pts[v][a]);
      }
    edge_sum += norm(pts[t[1]] - pts[t[0]]) + norm(pts[t[2]] - pts[t[1]]) + norm(pts[t[0]] - pts[t[2]]);
  }
  lo_ = lo;
  const double triangles = static_cast<double>(surface.triangles.size());
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  // Cells of the mean edge hold a few triangles each (measured: faster than twice or 0.6 times
  // that on a 1 M-triangle surface); grow them while the grid would be much larger than the
  // surface (a small surface in a big empty box).
  double cell = edge_sum / (3.0 * triangles);
  if (!(cell > 0.0)) cell = extent > 0.0 ? extent : 1.0;
  auto count_cells = [&](double h) {
    double total = 1.0;
    for (int a = 0; a < 3; ++a)
      total *= std::floor((hi[a] - lo[a]) / h) + 1.0;
    return total;
  };
  while (count_cells(cell) > max_cells_per_triangle * triangles + 64.0)
    cell *= 1.25;
  cell_ = cell;
  for (int a = 0; a < 3; ++a)
    dims_[a] = static_cast<std::int64_t>(std::floor((hi[a] - lo[a]) / cell)) + 1;

  spheres_.reserve(surface.triangles.size());
  for (const Triangle& t : surface.triangles) {
    const Point center = (1.0 / 3.0) * (pts[t[0]] + pts[t[1]] + pts[t[2]]);
    const double radius =
        std::sqrt(std::max({norm2(pts[t[0]] - center), norm2(pts[t[1]] - center), norm2(pts[t[2]] - center)}));
    spheres_.push_back({center[0], center[1], center[2], radius});
  }

  const std::size_t cells = static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]);
  offsets_.assign(cells + 1, 0);
  auto for_cells = [&](const Triangle& t, auto&& fn) {
    std::int64_t c0[3], c1[3];
    for (int a = 0; a < 3; ++a) {
      const double mn = std::min({pts[t[0]][a], pts[t[1]][a], pts[t[2]][a]});
      const double mx = std::max({pts[t[0]][a], pts[t[1]][a], pts[t[2]][a]});
      c0[a] = cell_of(mn, a);
      c1[a] = cell_of(mx, a);
    }
    for (std::int64_t x = c0[0]; x <= c1[0]; ++x)
      for (std::int64_t y = c0[1]; y <= c1[1]; ++y)
        for (std::int64_t z = c0[2]; z <= c1[2]; ++z)
          fn(static_cast<std::size_t>((x * dims_[1] + y) * dims_[2] + z));
  };
  for (const Triangle& t : surface.triangles)
    for_cells(t, [&](std::size_t c) { ++offsets_[c + 1]; });
  for (std::size_t c = 0; c < cells; ++c)
    offsets_[c + 1] += offsets_[c];
  entries_.resize(offsets_[cells]);
  std::vector<std::size_t> cursor(offsets_.begin(), offsets_.end() - 1);
  for (std::size_t t = 0; t < surface.triangles.size(); ++t)
    for_cells(surface.triangles[t], [&](std::size_t c) { entries_[cursor[c]++] = static_cast<std::uint32_t>(t); });
}

TriangleGrid::Scratch TriangleGrid::make_scratch() const {
  return Scratch{std::vector<std::uint32_t>(surface_->triangles.size(), 0), 0};
}

std::int64_t TriangleGrid::cell_of(double x, int axis) const {
  const double f = std::floor((x - lo_[axis]) / cell_);
  if (!(f > 0.0)) return 0; // also NaN
  return std::min(static_cast<std::int64_t>(std::min(f, 9e18)), dims_[axis] - 1);
}

double TriangleGrid::distance2_to_cell(const Point& p, std::int64_t ix, std::int64_t iy, std::int64_t iz) const {
  const std::int64_t idx[3] = {ix, iy, iz};
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double c0 = lo_[a] + static_cast<double>(idx[a]) * cell_;
    const double c1 = c0 + cell_;
    const double d = p[a] < c0 ? c0 - p[a] : (p[a] > c1 ? p[a] - c1 : 0.0);
    d2 += d * d;
  }
  return d2;
}

void TriangleGrid::visit_cell(const Point& p, std::int64_t ix, std::int64_t iy, std::int64_t iz, Scratch& scratch,
                              double& best) const {
  const auto c = static_cast<std::size_t>((ix * dims_[1] + iy) * dims_[2] + iz);
  if (offsets_[c] == offsets_[c + 1] || distance2_to_cell(p, ix, iy, iz) >= best) return;
  const auto& pts = surface_->points;
  for (std::size_t e = offsets_[c]; e < offsets_[c + 1]; ++e) {
    const std::uint32_t t = entries_[e];
    if (scratch.stamp[t] == scratch.query) continue;
    scratch.stamp[t] = scratch.query;
    // A triangle whose bounding sphere is farther than the best so far cannot be nearer.
    const auto& sphere = spheres_[t];
    const double dx = p[0] - sphere[0], dy = p[1] - sphere[1], dz = p[2] - sphere[2];
    const double gap = std::sqrt(dx * dx + dy * dy + dz * dz) - sphere[3];
    if (gap > 0.0 && gap * gap >= best) continue;
    const Triangle& tri = surface_->triangles[t];
    best = std::min(best, point_triangle_distance2(p, pts[tri[0]], pts[tri[1]], pts[tri[2]]));
  }
}

double TriangleGrid::nearest_distance2(const Point& p, Scratch& scratch) const {
  if (++scratch.query == 0) { // the stamps wrapped around: start afresh
    std::fill(scratch.stamp.begin(), scratch.stamp.end(), 0);
    scratch.query = 1;
  }
  const std::int64_t c[3] = {cell_of(p[0], 0), cell_of(p[1], 1), cell_of(p[2], 2)};
  double best = std::numeric_limits<double>::infinity();
  for (std::int64_t r = 0;; ++r) {
    // Visit the shell of cells at Chebyshev distance r from c, clipped to the grid.
    std::int64_t from[3], to[3];
    for (int a = 0; a < 3; ++a) {
      from[a] = std::max<std::int64_t>(c[a] - r, 0);
      to[a] = std::min<std::int64_t>(c[a] + r, dims_[a] - 1);
    }
    for (std::int64_t x = from[0]; x <= to[0]; ++x) {
      const bool x_face = x == c[0] - r || x == c[0] + r;
      for (std::int64_t y = from[1]; y <= to[1]; ++y) {
        const bool y_face = y == c[1] - r || y == c[1] + r;
        if (x_face || y_face) {
          for (std::int64_t z = from[2]; z <= to[2]; ++z)
            visit_cell(p, x, y, z, scratch, best);
        } else {
          if (c[2] - r >= 0) visit_cell(p, x, y, c[2] - r, scratch, best);
          if (r > 0 && c[2] + r < dims_[2]) visit_cell(p, x, y, c[2] + r, scratch, best);
        }
      }
    }
    // Every cell not yet visited lies beyond the block [c - r, c + r] along some axis, so it is at
    // least as far as the nearest side of the block that still has cells beyond it.
    double bound = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      if (c[a] - r - 1 >= 0)
        bound = std::min(bound, std::max(0.0, p[a] - (lo_[a] + static_cast<double>(c[a] - r) * cell_)));
      if (c[a] + r + 1 < dims_[a])
        bound = std::min(bound, std::max(0.0, lo_[a] + static_cast<double>(c[a] + r + 1) * cell_ - p[a]));
    }
    if (bound == std::numeric_limits<double>::infinity() || bound * bound >= best) return best;
  }
}

} // namespace geotandem::mesh::detail
