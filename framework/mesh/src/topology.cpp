// check_topology: one pass over the vertex stars (edges, fans), one over the triangles (areas,
// connectivity).

#include "geotandem/mesh/topology.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "stars.hpp"
#include "union_find.hpp"

namespace geotandem::mesh {

namespace {

// A triangle is flat when twice its area is below this fraction of its longest squared edge: that
// is collinear up to rounding, whatever the scale of the coordinates.
constexpr double flat_tolerance = 1e-12;

bool is_flat(const Point& a, const Point& b, const Point& c) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double x = u[1] * w[2] - u[2] * w[1];
  const double y = u[2] * w[0] - u[0] * w[2];
  const double z = u[0] * w[1] - u[1] * w[0];
  const double twice_area = std::sqrt(x * x + y * y + z * z);
  auto sq = [](const Point& p, const Point& q) {
    return (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
  };
  const double longest = std::max({sq(a, b), sq(b, c), sq(c, a)});
  return !(twice_area > flat_tolerance * longest);
}

} // namespace

std::string TopologyReport::summary() const {
  std::ostringstream out;
  out << "V=" << vertices << " F=" << triangles << " components=" << components << " boundary_edges=" << boundary_edges
      << " non_manifold_edges=" << non_manifold_edges << " non_manifold_vertices=" << non_manifold_vertices
      << " misoriented_edges=" << misoriented_edges << " degenerate_triangles=" << degenerate_triangles
      << " unreferenced_vertices=" << unreferenced_vertices << " euler=" << euler_characteristic;
  return out.str();
}

TopologyReport check_topology(const SurfaceMesh& surface) {
  TopologyReport report;
  report.triangles = surface.triangles.size();
  const detail::VertexStars stars = detail::build_vertex_stars(surface);

  std::size_t edges = 0;
  detail::walk_stars(
      surface, stars,
      [&](const detail::EdgeVisit& e) {
        ++edges;
        if (e.count == 1)
          ++report.boundary_edges;
        else if (e.count >= 3)
          ++report.non_manifold_edges;
        else if (e.misoriented)
          ++report.misoriented_edges;
      },
      [&](std::uint32_t, std::uint32_t fans, std::uint32_t) {
        ++report.vertices;
        if (fans > 1) ++report.non_manifold_vertices;
      });
  report.unreferenced_vertices = surface.points.size() - report.vertices;

  detail::UnionFind sets(surface.points.size());
  std::size_t faces = 0;
  for (const Triangle& t : surface.triangles) {
    if (detail::repeats_index(t)) {
      ++report.degenerate_triangles;
      continue;
    }
    ++faces;
    if (is_flat(surface.points[t[0]], surface.points[t[1]], surface.points[t[2]])) ++report.degenerate_triangles;
    sets.unite(t[0], t[1]);
    sets.unite(t[0], t[2]);
  }
  for (std::size_t v = 0; v + 1 < stars.offsets.size(); ++v)
    if (stars.offsets[v + 1] != stars.offsets[v] && sets.find(static_cast<std::uint32_t>(v)) == v) ++report.components;

  report.euler_characteristic =
      static_cast<long>(report.vertices) - static_cast<long>(edges) + static_cast<long>(faces);
  return report;
}

} // namespace geotandem::mesh
