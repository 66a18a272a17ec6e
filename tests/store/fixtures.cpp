#include "fixtures.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>

#include "geotandem/mesh/measure.hpp"

namespace geotandem::store::testing {

volume::Geometry test_geometry() {
  volume::Geometry g;
  g.shape = {60, 50, 40};
  const double angle = 20.0 * std::numbers::pi / 180.0, bin = 25.0;
  g.affine = {612000.0, bin * std::sin(angle), bin * std::cos(angle),
              6.71e6,   bin * std::cos(angle), -bin * std::sin(angle)};
  g.z0 = 1000.0;
  g.dz = 4.0;
  return g;
}

mesh::SurfaceMesh icosphere(int level) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  mesh::SurfaceMesh s;
  s.points = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
              {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  s.triangles = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
    auto mid = [&](std::uint32_t a, std::uint32_t b) {
      auto edge = std::minmax(a, b);
      auto [it, fresh] = middle.emplace(edge, static_cast<std::uint32_t>(s.points.size()));
      if (fresh) {
        const auto &p = s.points[a], &q = s.points[b];
        s.points.push_back({(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2});
      }
      return it->second;
    };
    std::vector<mesh::Triangle> next;
    for (auto [a, b, c] : s.triangles) {
      auto ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.insert(next.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    s.triangles = std::move(next);
  }
  for (auto& p : s.points) {
    double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (double& c : p)
      c /= n;
  }
  return s;
}

mesh::Component make_component(std::uint64_t key, const volume::Geometry& geometry, int max_level) {
  std::mt19937_64 rng(key * 0x9e3779b97f4a7c15ull + 17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  mesh::Component c;
  c.key = key;
  const int level = static_cast<int>(rng() % static_cast<std::uint64_t>(max_level + 1));
  c.surface = icosphere(level);
  const double a = 1.0 + 5.0 * unit(rng), b = 1.0 + 3.0 * unit(rng), h = 1.0 + 2.0 * unit(rng);
  const double phi = std::numbers::pi * unit(rng);
  const double ci = 8 + 44 * unit(rng), cj = 8 + 34 * unit(rng), ck = 5 + 30 * unit(rng);
  for (auto& p : c.surface.points) {
    double x = a * p[0], y = b * p[1], z = h * p[2];
    p = {ci + x * std::cos(phi) - y * std::sin(phi), cj + x * std::sin(phi) + y * std::cos(phi), ck + z};
  }
  const auto world = mesh::to_world(c.surface, geometry);
  auto& s = c.stats;
  s.vertex_count = world.points.size();
  s.triangle_count = world.triangles.size();
  s.box_min = s.box_max = world.points.front();
  for (const auto& p : world.points)
    for (int d = 0; d < 3; ++d) {
      s.box_min[d] = std::min(s.box_min[d], p[d]);
      s.box_max[d] = std::max(s.box_max[d], p[d]);
      s.centroid[d] += p[d] / static_cast<double>(world.points.size());
    }
  const auto& f = geometry.affine;
  const double cell = std::abs(f.xi * f.yj - f.xj * f.yi) * geometry.dz;
  s.volume = 4.0 / 3.0 * std::numbers::pi * a * b * h * cell;
  s.area = 1000.0 * unit(rng);
  s.obb_center = s.centroid;
  s.obb_axes = {{{std::cos(phi), std::sin(phi), 0.0}, {-std::sin(phi), std::cos(phi), 0.0}, {0.0, 0.0, 1.0}}};
  s.obb_half_extents = {a * 25.0, b * 25.0, h * geometry.dz};
  // Azimuths land on whole and half degrees now and then, to exercise inclusive range ends.
  s.azimuth = (key % 7 == 0) ? static_cast<double>(key % 180) : 180.0 * unit(rng);
  s.dip = 90.0 * unit(rng);
  s.elongation = 1.0 - b / std::max(a, b);
  s.cut_by_border = key % 5 == 0;
  s.closed = !s.cut_by_border;
  if (s.cut_by_border) s.volume = 0.0;
  return c;
}

bool same_surface(const mesh::SurfaceMesh& a, const mesh::SurfaceMesh& b) {
  return a.points == b.points && a.triangles == b.triangles;
}

bool same_stats(const mesh::ComponentStats& a, const mesh::ComponentStats& b) {
  return a.vertex_count == b.vertex_count && a.triangle_count == b.triangle_count && a.closed == b.closed &&
         a.cut_by_border == b.cut_by_border && a.volume == b.volume && a.area == b.area && a.centroid == b.centroid &&
         a.box_min == b.box_min && a.box_max == b.box_max && a.obb_center == b.obb_center && a.obb_axes == b.obb_axes &&
         a.obb_half_extents == b.obb_half_extents && a.azimuth == b.azimuth && a.dip == b.dip &&
         a.elongation == b.elongation;
}

} // namespace geotandem::store::testing
