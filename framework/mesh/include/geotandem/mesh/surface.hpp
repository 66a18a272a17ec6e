#pragma once
// The plain triangle surface every part exchanges: the tandem algorithm produces it for a finished
// component, the store writes and reads it, metrics and exports consume it. OpenMesh stays inside
// the tandem part's working mesh; this type is a pair of flat arrays.

#include <array>
#include <cstdint>
#include <vector>

namespace geotandem::mesh {

using Point = std::array<double, 3>;
using Triangle = std::array<std::uint32_t, 3>;

// Triangles are oriented counter-clockwise seen from outside a body (from lower values towards
// higher values is "inside"), so that normals point out and the enclosed volume is positive.
// Coordinates are in index units (i, j, k) unless a function says it returns world coordinates.
struct SurfaceMesh {
  std::vector<Point> points;
  std::vector<Triangle> triangles;

  std::size_t vertex_count() const { return points.size(); }
  std::size_t triangle_count() const { return triangles.size(); }
  bool empty() const { return triangles.empty(); }
};

} // namespace geotandem::mesh
