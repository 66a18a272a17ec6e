// The report's body views, from a component store: survey outline, decimated kept bodies and
// their footprints.

#include "geotandem/workflow/report_views.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>

namespace geotandem::workflow {
namespace {

double cross(const std::array<double, 2>& o, const std::array<double, 2>& a, const std::array<double, 2>& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

// Surface area in display coordinates, to size the first clustering cell.
double area_of(const std::vector<std::array<double, 3>>& p, const std::vector<mesh::Triangle>& triangles) {
  double area = 0.0;
  for (const auto& t : triangles) {
    const auto &a = p[t[0]], &b = p[t[1]], &c = p[t[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  return area;
}

struct TripleHash {
  std::size_t operator()(const std::array<std::uint32_t, 3>& t) const noexcept {
    std::uint64_t h = t[0];
    h = h * 0x9E3779B97F4A7C15ull ^ t[1];
    h = h * 0x9E3779B97F4A7C15ull ^ t[2];
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

struct Clustered {
  std::vector<std::array<double, 3>> points;
  std::vector<mesh::Triangle> triangles;
};

// Vertex clustering on a grid of `cell`: the vertices of a cell merge into their mean; triangles
// whose corners fall in three different cells survive, once each.
Clustered cluster(const std::vector<std::array<double, 3>>& p, const std::vector<mesh::Triangle>& triangles,
                  double cell) {
  Clustered out;
  // Cells are counted from the body's lowest corner, 21 bits per axis: a cell at least 2^-20 of
  // the largest extent keeps every index in range.
  std::array<double, 3> lo{}, hi{};
  for (int a = 0; a < 3; ++a) {
    lo[a] = hi[a] = p.empty() ? 0.0 : p[0][a];
    for (const auto& q : p)
      lo[a] = std::min(lo[a], q[a]), hi[a] = std::max(hi[a], q[a]);
    cell = std::max(cell, (hi[a] - lo[a]) / double(1 << 20));
  }
  std::unordered_map<std::uint64_t, std::uint32_t> cell_index;
  std::vector<std::uint32_t> of_vertex(p.size());
  std::vector<double> count;
  for (std::size_t v = 0; v < p.size(); ++v) {
    std::uint64_t id = 0;
    for (int a = 0; a < 3; ++a)
      id = id << 21 | (static_cast<std::uint64_t>((p[v][a] - lo[a]) / cell) & 0x1FFFFF);
    auto [it, added] = cell_index.try_emplace(id, static_cast<std::uint32_t>(out.points.size()));
    if (added) {
      out.points.push_back({0, 0, 0});
      count.push_back(0);
    }
    of_vertex[v] = it->second;
    for (int a = 0; a < 3; ++a)
      out.points[it->second][a] += p[v][a];
    count[it->second] += 1;
  }
  for (std::size_t c = 0; c < out.points.size(); ++c)
    for (int a = 0; a < 3; ++a)
      out.points[c][a] /= count[c];
  std::unordered_set<std::array<std::uint32_t, 3>, TripleHash> seen;
  for (const auto& t : triangles) {
    mesh::Triangle m{of_vertex[t[0]], of_vertex[t[1]], of_vertex[t[2]]};
    if (m[0] == m[1] || m[1] == m[2] || m[0] == m[2]) continue;
    std::array<std::uint32_t, 3> sorted = m;
    std::sort(sorted.begin(), sorted.end());
    if (seen.insert(sorted).second) out.triangles.push_back(m);
  }
  return out;
}

} // namespace

ReportSurvey survey_outline(const volume::Geometry& g) {
  ReportSurvey s;
  const double li = static_cast<double>(g.shape[0] - 1), lj = static_cast<double>(g.shape[1] - 1);
  s.corners = {g.affine.apply(0, 0), g.affine.apply(li, 0), g.affine.apply(li, lj), g.affine.apply(0, lj)};
  s.z_min = g.z0;
  s.z_max = g.z0 + g.dz * static_cast<double>(g.shape[2] - 1);
  s.z_unit = volume::to_string(g.z_unit);
  s.crs = g.crs.label();
  s.xy_unit = g.crs.empty() ? std::string("m") : g.crs.unit;
  s.known = g.shape[0] > 0 && g.shape[1] > 0 && g.shape[2] > 0;
  return s;
}

double display_z_scale(const ReportSurvey& survey) {
  double width = 0.0;
  for (const auto& a : survey.corners)
    for (const auto& b : survey.corners)
      width = std::max(width, std::hypot(a[0] - b[0], a[1] - b[1]));
  const double height = survey.z_max - survey.z_min;
  if (!(width > 0.0) || !(height > 0.0)) return 1.0;
  return 0.5 * width / height;
}

std::vector<std::array<double, 2>> convex_hull(std::vector<std::array<double, 2>> p) {
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  std::vector<std::array<double, 2>> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t n = 0; n < p.size(); ++n) { // lower chain
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[n]) <= 0)
      --k;
    hull[k++] = p[n];
  }
  for (std::size_t n = p.size() - 1, lower = k + 1; n-- > 0;) { // upper chain
    while (k >= lower && cross(hull[k - 2], hull[k - 1], p[n]) <= 0)
      --k;
    hull[k++] = p[n];
  }
  hull.resize(k - 1);
  return hull;
}

ReportBody display_body(const ReportComponent& component, const mesh::SurfaceMesh& world,
                        const std::array<double, 2>& origin, double z_scale, std::size_t budget) {
  ReportBody body;
  body.key = component.key;
  body.volume = component.volume;
  body.azimuth = component.azimuth;
  body.closed = component.closed;
  body.full_triangles = world.triangle_count();
  std::vector<std::array<double, 2>> map(world.points.size());
  std::vector<std::array<double, 3>> display(world.points.size());
  for (std::size_t v = 0; v < world.points.size(); ++v) {
    const auto& p = world.points[v];
    map[v] = {p[0], p[1]};
    display[v] = {p[0] - origin[0], p[1] - origin[1], p[2] * z_scale};
  }
  body.footprint = convex_hull(map);

  Clustered kept{display, world.triangles};
  if (budget < 4) {
    // A share too small to draw anything recognisable: the body shows on the map only.
    kept.triangles.clear();
  } else if (world.triangle_count() > budget) {
    // About two triangles per occupied cell of a surface: start there, coarsen until it fits.
    double cell =
        std::sqrt(2.0 * area_of(display, world.triangles) / static_cast<double>(std::max<std::size_t>(budget, 1)));
    if (!(cell > 0.0)) cell = 1.0;
    for (int attempt = 0; attempt < 60; ++attempt, cell *= 1.25) {
      kept = cluster(display, world.triangles, cell);
      if (kept.triangles.size() <= budget) break;
    }
    if (kept.triangles.size() > budget) kept.triangles.clear();
  }
  // Only the points some triangle uses, renumbered.
  std::vector<std::uint32_t> index(kept.points.size(), UINT32_MAX);
  for (const auto& t : kept.triangles) {
    mesh::Triangle renumbered{};
    for (int c = 0; c < 3; ++c) {
      if (index[t[c]] == UINT32_MAX) {
        index[t[c]] = static_cast<std::uint32_t>(body.points.size());
        const auto& p = kept.points[t[c]];
        body.points.push_back({static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2] / z_scale)});
      }
      renumbered[c] = index[t[c]];
    }
    body.triangles.push_back(renumbered);
  }
  return body;
}

std::vector<ReportBody> display_bodies(const store::ComponentStore& store,
                                       const std::vector<ReportComponent>& components, const ReportSurvey& survey,
                                       std::size_t budget, std::size_t max_bodies, const CancelToken* cancel) {
  std::vector<std::size_t> shown;
  for (std::size_t i = 0; i < components.size(); ++i)
    if (components[i].kept) shown.push_back(i);
  if (shown.size() > max_bodies) {
    std::nth_element(shown.begin(), shown.begin() + static_cast<std::ptrdiff_t>(max_bodies), shown.end(),
                     [&](std::size_t a, std::size_t b) {
                       if (components[a].triangles != components[b].triangles)
                         return components[a].triangles > components[b].triangles;
                       return a < b;
                     });
    shown.resize(max_bodies);
    std::sort(shown.begin(), shown.end());
  }
  std::uint64_t total = 0;
  for (std::size_t i : shown)
    total += components[i].triangles;
  const double z_scale = display_z_scale(survey);
  std::vector<ReportBody> bodies;
  bodies.reserve(shown.size());
  for (std::size_t i : shown) {
    if (cancel) cancel->throw_if_cancelled(); // reading and decimating a large body takes a while
    const ReportComponent& c = components[i];
    // Each body's share of the budget, in proportion to its triangles: the sum stays within it.
    const auto share = static_cast<std::size_t>(static_cast<double>(budget) * static_cast<double>(c.triangles) /
                                                static_cast<double>(std::max<std::uint64_t>(total, 1)));
    bodies.push_back(display_body(c, store.read(c.key), survey.corners[0], z_scale, share));
  }
  return bodies;
}

} // namespace geotandem::workflow
