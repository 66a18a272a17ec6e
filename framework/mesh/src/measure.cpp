// World mapping and the measures of one component (design section 7).

#include "geotandem/mesh/measure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/caps.hpp"
#include "geotandem/mesh/quality.hpp"
#include "geotandem/mesh/vec.hpp"
#include "stars.hpp"

namespace geotandem::mesh {

using namespace detail;

namespace {

constexpr double to_deg = 180.0 / std::numbers::pi;

// Makes an axis' largest component positive, so that the same body always gets the same axes.
std::array<double, 3> canonical_sign(const Eigen::Vector3d& v) {
  Eigen::Index largest = 0;
  v.cwiseAbs().maxCoeff(&largest);
  const double s = v[largest] < 0.0 ? -1.0 : 1.0;
  return {s * v[0], s * v[1], s * v[2]};
}

double axial_degrees(double deg) {
  double r = std::fmod(deg, 180.0);
  if (r < 0.0) r += 180.0;
  return r >= 180.0 ? 0.0 : r;
}

} // namespace

SurfaceMesh to_world(const SurfaceMesh& index_surface, const volume::Geometry& geometry) {
  const auto& f = geometry.affine;
  const double det = (f.xi * f.yj - f.xj * f.yi) * geometry.dz;
  if (!(std::abs(det) > 0.0) || !std::isfinite(det))
    throw InvalidArgument("cannot map a surface to world coordinates: the survey affine and sample interval are "
                          "degenerate (determinant " +
                              std::to_string(det) + ")",
                          {}, "check the geometry's affine (xi, xj, yi, yj) and dz");
  SurfaceMesh world;
  world.points.reserve(index_surface.points.size());
  for (const Point& p : index_surface.points)
    world.points.push_back(geometry.world(p[0], p[1], p[2]));
  world.triangles = index_surface.triangles;
  // A mirror map turns counter-clockwise into clockwise: swap two corners to keep normals outward.
  if (det < 0.0)
    for (Triangle& t : world.triangles)
      std::swap(t[1], t[2]);
  return world;
}

ComponentStats measure_component(const SurfaceMesh& index_surface, const volume::Geometry& geometry) {
  if (index_surface.triangles.empty())
    throw InvalidArgument("cannot measure a component without triangles", {},
                          "drop empty components before measuring them");
  geometry.validate();
  ComponentStats stats;
  stats.vertex_count = index_surface.points.size();
  stats.triangle_count = index_surface.triangles.size();

  // Topology in index space, where the cube's outer planes are exact.
  const VertexStars stars = build_vertex_stars(index_surface);
  bool closed = true;
  walk_stars(
      index_surface, stars,
      [&](const EdgeVisit& e) {
        if (e.count != 2) closed = false;
      },
      [](std::uint32_t, std::uint32_t, std::uint32_t) {});
  // Cut faces: the outer planes the surface has a corner on. Only a lattice edge in an outer plane
  // puts a marching-cubes vertex there, so the body reaches that face; a simplified vertex on a
  // face keeps its coordinate there. Cap triangles alone would not do: a body that reaches a face
  // at one sample equal to the isovalue gets a cap 1/256 voxel wide, which simplification removes
  // in some block layouts and not in others.
  std::uint8_t cut = 0;
  std::vector<bool> cap(index_surface.triangles.size(), false);
  for (std::size_t t = 0; t < cap.size(); ++t) {
    const Triangle& corners = index_surface.triangles[t];
    const std::uint8_t a = outer_planes(index_surface.points[corners[0]], geometry.shape),
                       b = outer_planes(index_surface.points[corners[1]], geometry.shape),
                       c = outer_planes(index_surface.points[corners[2]], geometry.shape);
    cut |= static_cast<std::uint8_t>(a | b | c);
    cap[t] = (a & b & c) != 0 && cap_face(index_surface, corners, geometry.shape) >= 0; // on a plane: a cap?
  }
  stats.closed = closed;
  stats.cut_faces = cut;
  stats.cut_by_border = cut != 0;

  const SurfaceMesh world = to_world(index_surface, geometry);
  stats.volume = closed ? enclosed_volume(world) : 0.0;

  // Area, centroid and second moments of the surface as a uniform sheet. Relative to a surface
  // point, so that world coordinates of 10^6 m keep their digits. A triangle's second moment is
  // area/12 (sum v v^T + s s^T) with s the sum of its corners.
  const Point origin = world.points[world.triangles.front()[0]];
  double area = 0.0;
  Point first{};
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  // Plain loops rather than Eigen expressions per triangle: the same speed optimised, and many
  // times faster in the debug and sanitizer builds that the tests run in.
  auto add_outer = [&second](const Point& v, double w) {
    for (int r = 0; r < 3; ++r)
      for (int c = r; c < 3; ++c)
        second(r, c) += w * v[r] * v[c];
  };
  double cap_area = 0.0;
  for (std::size_t n = 0; n < world.triangles.size(); ++n) {
    const Triangle& t = world.triangles[n];
    const Point a = world.points[t[0]] - origin, b = world.points[t[1]] - origin, c = world.points[t[2]] - origin;
    const double w = 0.5 * norm(cross(b - a, c - a));
    const Point s = a + b + c;
    area += w;
    if (cap[n]) cap_area += w;
    first = first + (w / 3.0) * s;
    for (const Point* v : {&a, &b, &c, &s})
      add_outer(*v, w / 12.0);
  }
  double total = area;
  if (!(area > 0.0)) {
    // Every triangle is flat: fall back to the corners with equal weights.
    first = {};
    second.setZero();
    for (const Triangle& t : world.triangles)
      for (std::uint32_t v : t) {
        const Point p = world.points[v] - origin;
        first = first + p;
        add_outer(p, 1.0);
      }
    total = 3.0 * static_cast<double>(world.triangles.size());
  }
  // A closed surface (a body closed by itself or by caps) is measured as the solid it encloses:
  // moments of the tetrahedra from the origin to each triangle (divergence theorem). A tetrahedron
  // (0, a, b, c) of signed volume V has first moment V (a + b + c) / 4 and second moment
  // V/20 (a a^T + b b^T + c c^T + s s^T), s = a + b + c.
  if (closed && stats.volume > 0.0) {
    double solid = 0.0;
    Point solid_first{};
    Eigen::Matrix3d solid_second = Eigen::Matrix3d::Zero();
    for (const Triangle& t : world.triangles) {
      const Point a = world.points[t[0]] - origin, b = world.points[t[1]] - origin, c = world.points[t[2]] - origin;
      const double v = dot(a, cross(b, c)) / 6.0;
      const Point s = a + b + c;
      solid += v;
      solid_first = solid_first + (v / 4.0) * s;
      for (const Point* p : {&a, &b, &c, &s})
        for (int r = 0; r < 3; ++r)
          for (int q = r; q < 3; ++q)
            solid_second(r, q) += v / 20.0 * (*p)[r] * (*p)[q];
    }
    if (solid > 0.0) {
      first = solid_first;
      second = solid_second;
      total = solid;
    }
  }
  first = (1.0 / total) * first;
  second /= total;
  stats.area = area;
  stats.cap_area = cap_area;
  const Eigen::Vector3d f(first[0], first[1], first[2]);
  Eigen::Matrix3d covariance = second - f * f.transpose();
  covariance.triangularView<Eigen::StrictlyLower>() = covariance.transpose().triangularView<Eigen::StrictlyLower>();
  const Point centroid = origin + first;
  stats.centroid = centroid;

  // Boxes over the vertices the triangles use.
  std::vector<bool> used(world.points.size(), false);
  for (const Triangle& t : world.triangles)
    for (std::uint32_t v : t)
      used[v] = true;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  stats.obb_axes[0] = canonical_sign(solver.eigenvectors().col(2));
  stats.obb_axes[1] = canonical_sign(solver.eigenvectors().col(1));
  stats.obb_axes[2] = cross(stats.obb_axes[0], stats.obb_axes[1]);
  constexpr double inf = std::numeric_limits<double>::infinity();
  Point lo{inf, inf, inf}, hi{-inf, -inf, -inf}, along_lo = lo, along_hi = hi;
  for (std::size_t v = 0; v < world.points.size(); ++v) {
    if (!used[v]) continue;
    const Point& p = world.points[v];
    const Point rel = p - centroid;
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
      const double s = dot(rel, stats.obb_axes[a]);
      along_lo[a] = std::min(along_lo[a], s);
      along_hi[a] = std::max(along_hi[a], s);
    }
  }
  stats.box_min = lo;
  stats.box_max = hi;
  stats.obb_center = centroid;
  for (int a = 0; a < 3; ++a) {
    stats.obb_center = stats.obb_center + (0.5 * (along_lo[a] + along_hi[a])) * stats.obb_axes[a];
    stats.obb_half_extents[a] = 0.5 * (along_hi[a] - along_lo[a]);
  }

  // Main horizontal axis: principal direction of the (x, y) block of the covariance. Its angle
  // from east is theta = 1/2 atan2(2 cxy, cxx - cyy); the azimuth from north is 90 - theta.
  const double cxx = covariance(0, 0), cyy = covariance(1, 1), cxy = covariance(0, 1);
  const double theta = 0.5 * std::atan2(2.0 * cxy, cxx - cyy);
  stats.azimuth = axial_degrees(90.0 - theta * to_deg);
  const double spread = std::hypot(cxx - cyy, 2.0 * cxy);
  const double l1 = 0.5 * (cxx + cyy + spread), l2 = std::max(0.0, 0.5 * (cxx + cyy - spread));
  stats.elongation = l1 > 0.0 ? std::clamp(1.0 - std::sqrt(l2 / l1), 0.0, 1.0) : 0.0;

  const auto& main = stats.obb_axes[0];
  stats.dip = std::atan2(std::abs(main[2]), std::hypot(main[0], main[1])) * to_deg;
  return stats;
}

} // namespace geotandem::mesh
