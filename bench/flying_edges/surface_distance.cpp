// Distances, shape and edge counts of triangle soups (see surface_distance.hpp).

#include "flying_edges/surface_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace geotandem::bench {
namespace {

struct V {
  double x, y, z;
};
V operator-(V a, V b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
V operator+(V a, V b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
V operator*(double s, V a) {
  return {s * a.x, s * a.y, s * a.z};
}
double dot(V a, V b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
V cross(V a, V b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

V vertex(const Surface& s, std::uint32_t v) {
  const float* p = s.xyz.data() + 3 * static_cast<std::size_t>(v);
  return {p[0], p[1], p[2]};
}

// The closest point of triangle abc to p, by its Voronoi regions (Ericson, Real-Time Collision
// Detection, 5.1.5); degenerate triangles fall into an edge or vertex region.
V closest_on_triangle(V p, V a, V b, V c) {
  const V ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const V bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;
  const V cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = va + vb + vc;
  if (!(denom > 0.0)) return a; // a triangle of zero area whose regions all failed: its corner a
  return a + (vb / denom) * ab + (vc / denom) * ac;
}

} // namespace

TriangleGrid::TriangleGrid(const Surface& surface, double cell) : surface_(surface), cell_(cell) {
  if (!(cell > 0.0)) throw std::invalid_argument("TriangleGrid: the cell size must be positive");
  stamp_.assign(surface.triangles(), 0);
  if (surface.triangles() == 0) {
    start_.assign(2, 0);
    return;
  }
  double hi[3];
  for (int a = 0; a < 3; ++a) {
    lo_[a] = std::numeric_limits<double>::infinity();
    hi[a] = -std::numeric_limits<double>::infinity();
  }
  for (std::size_t v = 0; v < surface.vertices(); ++v)
    for (int a = 0; a < 3; ++a) {
      lo_[a] = std::min(lo_[a], static_cast<double>(surface.xyz[3 * v + static_cast<std::size_t>(a)]));
      hi[a] = std::max(hi[a], static_cast<double>(surface.xyz[3 * v + static_cast<std::size_t>(a)]));
    }
  for (int a = 0; a < 3; ++a)
    dims_[a] = static_cast<std::int64_t>(std::floor((hi[a] - lo_[a]) / cell_)) + 1;
  const auto cells = static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]);
  if (cells >= std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("TriangleGrid: too many cells; use larger ones");

  // Each triangle goes into every cell its bounding box meets: counted, then placed (CSR).
  auto cell_range = [&](std::uint32_t t, std::int64_t lo[3], std::int64_t up[3]) {
    for (int a = 0; a < 3; ++a) {
      double mn = std::numeric_limits<double>::infinity(), mx = -mn;
      for (int c = 0; c < 3; ++c) {
        const double x =
            surface.xyz[3 * surface.corners[3 * static_cast<std::size_t>(t) + static_cast<std::size_t>(c)] +
                        static_cast<std::size_t>(a)];
        mn = std::min(mn, x);
        mx = std::max(mx, x);
      }
      lo[a] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((mn - lo_[a]) / cell_)), 0, dims_[a] - 1);
      up[a] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((mx - lo_[a]) / cell_)), 0, dims_[a] - 1);
    }
  };
  std::vector<std::uint32_t> count(cells + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    for (std::uint32_t t = 0; t < surface.triangles(); ++t) {
      std::int64_t lo[3], up[3];
      cell_range(t, lo, up);
      for (std::int64_t i = lo[0]; i <= up[0]; ++i)
        for (std::int64_t j = lo[1]; j <= up[1]; ++j)
          for (std::int64_t k = lo[2]; k <= up[2]; ++k) {
            const auto n = static_cast<std::size_t>((i * dims_[1] + j) * dims_[2] + k);
            if (pass == 0)
              ++count[n + 1];
            else
              triangles_[start_[n] + count[n]++] = t;
          }
    }
    if (pass == 0) {
      for (std::size_t n = 0; n < cells; ++n)
        count[n + 1] += count[n];
      if (count[cells] >= std::numeric_limits<std::uint32_t>::max())
        throw std::invalid_argument("TriangleGrid: too many triangle-cell pairs; use larger cells");
      start_ = count;
      triangles_.resize(count[cells]);
      std::fill(count.begin(), count.end(), 0);
    }
  }
}

double TriangleGrid::point_triangle(const double p[3], std::uint32_t t) const {
  const std::uint32_t* c = surface_.corners.data() + 3 * static_cast<std::size_t>(t);
  const V q{p[0], p[1], p[2]};
  const V d = q - closest_on_triangle(q, vertex(surface_, c[0]), vertex(surface_, c[1]), vertex(surface_, c[2]));
  return std::sqrt(dot(d, d));
}

double TriangleGrid::distance(const double p[3]) const {
  if (triangles_.empty()) return std::numeric_limits<double>::infinity();
  if (++query_ == 0) { // the stamps wrapped: start them again
    std::fill(stamp_.begin(), stamp_.end(), 0);
    query_ = 1;
  }
  std::int64_t c[3];
  for (int a = 0; a < 3; ++a) {
    const double f = std::clamp(std::floor((p[a] - lo_[a]) / cell_), 0.0, static_cast<double>(dims_[a] - 1));
    c[a] = static_cast<std::int64_t>(f);
  }
  double best = std::numeric_limits<double>::infinity();
  // Rings of cells at Chebyshev distance r from p's cell (the nearest cell when p is outside the
  // grid). After ring r every cell left lies beyond a face of the box of cells [c - r, c + r] that
  // has cells beyond it, so no triangle of theirs is nearer than p's distance to that half-space.
  for (std::int64_t r = 0;; ++r) {
    std::int64_t lo[3], up[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max<std::int64_t>(0, c[a] - r);
      up[a] = std::min<std::int64_t>(dims_[a] - 1, c[a] + r);
    }
    for (std::int64_t i = lo[0]; i <= up[0]; ++i)
      for (std::int64_t j = lo[1]; j <= up[1]; ++j) {
        const bool shell_ij = std::abs(i - c[0]) == r || std::abs(j - c[1]) == r;
        for (std::int64_t k = lo[2]; k <= up[2]; ++k) {
          if (!shell_ij && std::abs(k - c[2]) != r) {
            k = std::max(k, c[2] + r - 1); // the inside of the ring was visited: jump to its far side
            continue;
          }
          const auto n = static_cast<std::size_t>((i * dims_[1] + j) * dims_[2] + k);
          if (start_[n] == start_[n + 1]) continue;
          // A cell whose box is no nearer than the best triangle so far cannot hold a nearer one.
          const std::int64_t ijk[3] = {i, j, k};
          double gap2 = 0.0;
          for (int a = 0; a < 3; ++a) {
            const double lo_a = lo_[a] + static_cast<double>(ijk[a]) * cell_;
            const double g = std::max({0.0, lo_a - p[a], p[a] - (lo_a + cell_)});
            gap2 += g * g;
          }
          if (gap2 >= best * best) continue;
          for (std::uint32_t e = start_[n]; e < start_[n + 1]; ++e) {
            const std::uint32_t t = triangles_[e];
            if (stamp_[t] == query_) continue;
            stamp_[t] = query_;
            best = std::min(best, point_triangle(p, t));
          }
        }
      }
    bool all = true;
    double bound = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      if (lo[a] > 0) {
        all = false;
        bound = std::min(bound, std::max(0.0, p[a] - (lo_[a] + static_cast<double>(lo[a]) * cell_)));
      }
      if (up[a] < dims_[a] - 1) {
        all = false;
        bound = std::min(bound, std::max(0.0, (lo_[a] + static_cast<double>(up[a] + 1) * cell_) - p[a]));
      }
    }
    if (all || best <= bound) return best;
  }
}

Sampled sampled_distance(const Surface& from, const TriangleGrid& to, double spacing, const Box& inside,
                         double beyond) {
  Sampled out;
  auto measure = [&](V p, double area) {
    const double q[3] = {p.x, p.y, p.z};
    const double d = to.distance(q);
    const bool in = inside.contains(q);
    for (Distance* x : {&out.all, in ? &out.inside : nullptr}) {
      if (x == nullptr) continue;
      if (d > x->max) {
        x->max = d;
        std::copy(q, q + 3, x->where);
      }
      ++x->samples;
      x->weighted_sum += d * area;
      x->area += area;
      if (d > beyond) x->area_beyond += area;
    }
  };
  std::vector<char> vertex_done(from.vertices(), 0);
  for (std::size_t t = 0; t < from.triangles(); ++t) {
    const std::uint32_t* c = from.corners.data() + 3 * t;
    const V a = vertex(from, c[0]), b = vertex(from, c[1]), e = vertex(from, c[2]);
    const V u = b - a, w = e - a;
    const double longest = std::sqrt(std::max({dot(u, u), dot(w, w), dot(e - b, e - b)}));
    const auto m = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(longest / spacing)));
    const double step = 1.0 / static_cast<double>(m);
    // Corners of the sub-triangles, for the maximum only: the triangle's own corners once per vertex.
    for (std::int64_t i = 0; i <= m; ++i)
      for (std::int64_t j = 0; i + j <= m; ++j) {
        const int corner = i == 0 && j == 0 ? 0 : i == m ? 1 : j == m ? 2 : -1;
        if (corner >= 0) {
          if (!vertex_done[c[corner]]) measure(vertex(from, c[corner]), 0.0);
          vertex_done[c[corner]] = 1;
          continue;
        }
        measure(a + (static_cast<double>(i) * step) * u + (static_cast<double>(j) * step) * w, 0.0);
      }
    // Centroids of the m^2 sub-triangles, each for 1 / m^2 of the area.
    const double share = 0.5 * std::sqrt(dot(cross(u, w), cross(u, w))) * step * step;
    for (std::int64_t i = 0; i < m; ++i)
      for (std::int64_t j = 0; i + j < m; ++j) {
        measure(a + ((static_cast<double>(i) + 1.0 / 3.0) * step) * u +
                    ((static_cast<double>(j) + 1.0 / 3.0) * step) * w,
                share);
        if (i + j + 2 <= m)
          measure(a + ((static_cast<double>(i) + 2.0 / 3.0) * step) * u +
                      ((static_cast<double>(j) + 2.0 / 3.0) * step) * w,
                  share);
      }
  }
  return out;
}

double anisotropy(const Surface& surface) {
  if (surface.triangles() == 0) return 0.0;
  double sum = 0.0;
  for (std::size_t t = 0; t < surface.triangles(); ++t) {
    const std::uint32_t* c = surface.corners.data() + 3 * t;
    const V a = vertex(surface, c[0]), b = vertex(surface, c[1]), e = vertex(surface, c[2]);
    const V g = (1.0 / 3.0) * (a + b + e);
    // The inertia matrix has rank 2: its trace is lambda1 + lambda2 and lambda1 * lambda2 is
    // |u x w|^2 / 27 (u, w two edges from one corner).
    const double trace = (dot(a - g, a - g) + dot(b - g, b - g) + dot(e - g, e - g)) / 3.0;
    const V n = cross(b - a, e - a);
    const double product = dot(n, n) / 27.0;
    if (!(product > 0.0)) continue; // a flat triangle counts as rho = 0
    const double lambda1 = 0.5 * (trace + std::sqrt(std::max(0.0, trace * trace - 4.0 * product)));
    sum += std::clamp(std::sqrt(product) / lambda1, 0.0, 1.0);
  }
  return 1.0 - sum / static_cast<double>(surface.triangles());
}

EdgeCounts count_edges(const Surface& surface) {
  EdgeCounts out;
  std::vector<std::uint64_t> edges;
  edges.reserve(surface.corners.size());
  for (std::size_t t = 0; t < surface.triangles(); ++t) {
    const std::uint32_t* c = surface.corners.data() + 3 * t;
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) {
      ++out.degenerate_triangles;
      continue;
    }
    for (int e = 0; e < 3; ++e) {
      const std::uint64_t p = c[e], q = c[(e + 1) % 3];
      edges.push_back(std::min(p, q) << 32 | std::max(p, q));
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i])
      ++j;
    if (j - i == 1) ++out.border;
    if (j - i > 2) ++out.non_manifold;
    i = j;
  }
  return out;
}

} // namespace geotandem::bench
