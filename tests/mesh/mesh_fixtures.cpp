#include "mesh_fixtures.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

namespace geotandem::mesh::fixtures {

namespace {

Point sub(const Point& a, const Point& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Point crossp(const Point& a, const Point& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dotp(const Point& a, const Point& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// For a convex body containing `inside`: turns each triangle so its normal points away from it.
void orient_outward(SurfaceMesh& s, const Point& inside) {
  for (Triangle& t : s.triangles) {
    const Point& a = s.points[t[0]];
    const Point n = crossp(sub(s.points[t[1]], a), sub(s.points[t[2]], a));
    if (dotp(n, sub(a, inside)) < 0.0) std::swap(t[1], t[2]);
  }
}

} // namespace

SurfaceMesh icosphere(int level, double radius, const Point& center) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  SurfaceMesh s;
  s.points = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
              {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  s.triangles = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  auto project = [](Point p) {
    const double n = std::sqrt(dotp(p, p));
    return Point{p[0] / n, p[1] / n, p[2] / n};
  };
  for (Point& p : s.points)
    p = project(p);
  orient_outward(s, {0, 0, 0});
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
    auto mid = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      const Point& p = s.points[a];
      const Point& q = s.points[b];
      s.points.push_back(project({p[0] + q[0], p[1] + q[1], p[2] + q[2]}));
      const auto id = static_cast<std::uint32_t>(s.points.size() - 1);
      middle.emplace(key, id);
      return id;
    };
    std::vector<Triangle> finer;
    for (const Triangle& t : s.triangles) {
      const std::uint32_t ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      finer.push_back({t[0], ab, ca});
      finer.push_back({t[1], bc, ab});
      finer.push_back({t[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    s.triangles = std::move(finer);
  }
  for (Point& p : s.points)
    p = {center[0] + radius * p[0], center[1] + radius * p[1], center[2] + radius * p[2]};
  return s;
}

SurfaceMesh torus(double R, double r, int nu, int nv) {
  SurfaceMesh s;
  const double two_pi = 2.0 * std::numbers::pi;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = two_pi * i / nu, v = two_pi * j / nv;
      s.points.push_back({(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>((i % nu) * nv + (j % nv)); };
  // dP/du x dP/dv points away from the tube's axis, so (u, v)-counter-clockwise is outward.
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return s;
}

SurfaceMesh box(const Point& lo, const Point& hi) {
  SurfaceMesh s;
  for (int c = 0; c < 8; ++c)
    s.points.push_back({c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]});
  // Each face as two triangles over its four corners (bit `axis` fixed to `side`).
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      std::vector<std::uint32_t> corners;
      for (std::uint32_t c = 0; c < 8; ++c)
        if (((c >> axis) & 1u) == static_cast<unsigned>(side)) corners.push_back(c);
      // corners 0 and 3 of this list are diagonal (they differ in both free bits).
      s.triangles.push_back({corners[0], corners[1], corners[3]});
      s.triangles.push_back({corners[0], corners[3], corners[2]});
    }
  orient_outward(s, {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2});
  return s;
}

SurfaceMesh tetrahedron(const Point& a, const Point& b, const Point& c, const Point& d) {
  SurfaceMesh s;
  s.points = {a, b, c, d};
  s.triangles = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  orient_outward(s,
                 {(a[0] + b[0] + c[0] + d[0]) / 4, (a[1] + b[1] + c[1] + d[1]) / 4, (a[2] + b[2] + c[2] + d[2]) / 4});
  return s;
}

SurfaceMesh disc(double radius, int rings, int segments, double height) {
  SurfaceMesh s;
  s.points.push_back({0, 0, height});
  const double two_pi = 2.0 * std::numbers::pi;
  for (int r = 1; r <= rings; ++r)
    for (int k = 0; k < segments; ++k) {
      const double rho = radius * r / rings, a = two_pi * k / segments;
      s.points.push_back({rho * std::cos(a), rho * std::sin(a), height});
    }
  auto id = [&](int r, int k) {
    return r == 0 ? 0u : static_cast<std::uint32_t>(1 + (r - 1) * segments + k % segments);
  };
  for (int k = 0; k < segments; ++k)
    s.triangles.push_back({0, id(1, k), id(1, k + 1)});
  for (int r = 1; r < rings; ++r)
    for (int k = 0; k < segments; ++k) {
      s.triangles.push_back({id(r, k), id(r + 1, k), id(r + 1, k + 1)});
      s.triangles.push_back({id(r, k), id(r + 1, k + 1), id(r, k + 1)});
    }
  return s;
}

SurfaceMesh hemisphere(double radius, int stacks, int slices) {
  SurfaceMesh s;
  s.points.push_back({0, 0, radius}); // pole
  const double half_pi = std::numbers::pi / 2, two_pi = 2.0 * std::numbers::pi;
  for (int i = 1; i <= stacks; ++i)
    for (int k = 0; k < slices; ++k) {
      const double polar = half_pi * i / stacks, a = two_pi * k / slices;
      s.points.push_back(
          {radius * std::sin(polar) * std::cos(a), radius * std::sin(polar) * std::sin(a), radius * std::cos(polar)});
    }
  auto id = [&](int i, int k) { return i == 0 ? 0u : static_cast<std::uint32_t>(1 + (i - 1) * slices + k % slices); };
  for (int k = 0; k < slices; ++k)
    s.triangles.push_back({0, id(1, k), id(1, k + 1)});
  for (int i = 1; i < stacks; ++i)
    for (int k = 0; k < slices; ++k) {
      s.triangles.push_back({id(i, k), id(i + 1, k), id(i + 1, k + 1)});
      s.triangles.push_back({id(i, k), id(i + 1, k + 1), id(i, k + 1)});
    }
  orient_outward(s, {0, 0, 0});
  return s;
}

SurfaceMesh merged(const SurfaceMesh& a, const SurfaceMesh& b) {
  SurfaceMesh s = a;
  const auto shift = static_cast<std::uint32_t>(a.points.size());
  s.points.insert(s.points.end(), b.points.begin(), b.points.end());
  for (const Triangle& t : b.triangles)
    s.triangles.push_back({t[0] + shift, t[1] + shift, t[2] + shift});
  return s;
}

SurfaceMesh transformed(const SurfaceMesh& s, const Point& scale, double azimuth_deg, double dip_deg,
                        const Point& center) {
  const double az = azimuth_deg * std::numbers::pi / 180.0, dip = dip_deg * std::numbers::pi / 180.0;
  SurfaceMesh out = s;
  for (Point& p : out.points) {
    const double x = scale[0] * p[0], y = scale[1] * p[1], z = scale[2] * p[2];
    // Dip: rotate in the (y, z) plane, +y towards +z.
    const double y1 = y * std::cos(dip) - z * std::sin(dip);
    const double z1 = y * std::sin(dip) + z * std::cos(dip);
    // Azimuth: +y (north) turns clockwise towards +x (east).
    const double x2 = x * std::cos(az) + y1 * std::sin(az);
    const double y2 = -x * std::sin(az) + y1 * std::cos(az);
    p = {center[0] + x2, center[1] + y2, center[2] + z1};
  }
  // Positive scales and rotations keep the handedness, so the orientation stays outward.
  return out;
}

Unwelded unwelded(const SurfaceMesh& s) {
  Unwelded u;
  for (const Triangle& t : s.triangles) {
    Triangle fresh{};
    for (int c = 0; c < 3; ++c) {
      fresh[c] = static_cast<std::uint32_t>(u.surface.points.size());
      u.surface.points.push_back(s.points[t[c]]);
      u.keys.push_back(t[c]);
    }
    u.surface.triangles.push_back(fresh);
  }
  return u;
}

} // namespace geotandem::mesh::fixtures
