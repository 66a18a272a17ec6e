#pragma once
// A uniform grid over the triangles of a surface, for nearest-triangle queries: each triangle is
// listed in every cell its bounding box overlaps, and a query searches shells of cells around the
// point until no unvisited cell can hold anything nearer than the best triangle found.

#include <array>
#include <cstdint>
#include <vector>

#include "geotandem/mesh/surface.hpp"

namespace geotandem::mesh::detail {

// Exact squared distance from p to the closed triangle abc (any shape, also collinear or a point).
double point_triangle_distance2(const Point& p, const Point& a, const Point& b, const Point& c);

class TriangleGrid {
public:
  // `surface` must outlive the grid and have at least one triangle with valid indices.
  explicit TriangleGrid(const SurfaceMesh& surface);

  // Per-caller scratch, so that one grid can serve several threads.
  struct Scratch {
    std::vector<std::uint32_t> stamp; // last query that tested each triangle
    std::uint32_t query = 0;
  };
  Scratch make_scratch() const;

  // Squared distance from p to the nearest triangle.
  double nearest_distance2(const Point& p, Scratch& scratch) const;

  std::array<std::int64_t, 3> dims() const { return dims_; }
  double cell_size() const { return cell_; }

private:
  std::int64_t cell_of(double x, int axis) const;
  double distance2_to_cell(const Point& p, std::int64_t ix, std::int64_t iy, std::int64_t iz) const;
  void visit_cell(const Point& p, std::int64_t ix, std::int64_t iy, std::int64_t iz, Scratch& scratch,
                  double& best) const;

  const SurfaceMesh* surface_;
  Point lo_{};
  double cell_ = 1.0;
  std::array<std::int64_t, 3> dims_{1, 1, 1};
  std::vector<std::size_t> offsets_;           // cell -> first entry, cell_count + 1
  std::vector<std::uint32_t> entries_;         // triangle ids per cell
  std::vector<std::array<double, 4>> spheres_; // per triangle: centroid and radius around it
};

} // namespace geotandem::mesh::detail
