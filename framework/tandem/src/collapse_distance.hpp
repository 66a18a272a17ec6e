#pragma once
// The E0 guarantee (docs/algorithm.md, "The E0 guarantee"): what a collapse ab -> c does to the
// distance bound.
//
// Every vertex v keeps a bound d_v (VertexRecord::tolerance), interpolated linearly over each
// triangle: the tolerance at a surface point. Invariant: every point p of the full-resolution
// surface lies within the tolerance at phi(p) of phi(p), phi the composition of the collapses' maps.
// The maps are continuous and onto, so the symmetric Hausdorff distance between the current
// surface and the full-resolution one is at most max_v d_v. A collapse maps the patch around a and
// b (the triangles of their stars) onto the patch around c and leaves everything else in place;
// d_c is chosen as the smallest value keeping the invariant for the map used, and the engine
// refuses a collapse whose d_c exceeds E0.
//
// Two maps, the smaller d_c wins:
// - the simplicial map (a and b to c, linear on each triangle): d_c = max(d_a + |a - c|,
//   d_b + |b - c|);
// - when both patches project one to one onto the plane normal to their common vector area (the
//   same for both, as they share their boundary), the map that keeps the projection: points move
//   along the normal only, by D = the difference of two piecewise-linear heights. The condition
//   tol_new >= tol_old + |D| is linear minus convex on each cell of the overlay of the two
//   projected triangulations, so it holds everywhere when it holds at the overlay's vertices
//   (a, b, c and the crossings of the old interior edges with the new ones); each gives a lower
//   bound on d_c. Tangential motion is free, which lets a flat or gently curved patch simplify.
// Collapses at the surface's boundary (cube faces, open block faces) use the simplicial map.

#include <algorithm>
#include <array>
#include <limits>
#include <vector>

#include "working_mesh.hpp"

namespace geotandem::tandem::detail {

// The bound d_c of collapsing h (a = from, b = to, both moved to c); `points` and `records` are the
// mesh's points and vertex records. Scratch storage is kept between calls (one object per working
// surface).
class CollapseDistance {
public:
  // Values above `limit` (E0) are only known to be above it.
  double tolerance(const HalfedgeMesh& mesh, HH h, const Vec3& c, const HalfedgeMesh::Point* points,
                   const VertexRecord* records, double limit = std::numeric_limits<double>::infinity()) {
    gather(mesh, h, points, records);
    return bound(c, limit);
  }
  // The same in two steps, for several positions c of one collapse: gather() reads the patch
  // around h (and what of the projection does not depend on c), bound() gives d_c for one c. The
  // patch is only valid until the mesh, its points or their bounds change.
  void gather(const HalfedgeMesh& mesh, HH h, const HalfedgeMesh::Point* points, const VertexRecord* records);
  double bound(const Vec3& c, double limit = std::numeric_limits<double>::infinity());

  // d_c for the simplicial map alone (exposed for tests).
  static double simplicial(const Vec3& a, double da, const Vec3& b, double db, const Vec3& c);

private:
  // d_c for the projection map, or a negative value when the projection is not one to one.
  // Gives up (negative) as soon as d_c would exceed `limit`.
  double projected(const Vec3& c, double limit);

  // Local numbering: 0 = a, 1 = b, 2 = c, then the link vertices.
  struct Point2 {
    double u = 0.0, v = 0.0, z = 0.0;
  };
  // Scratch arrays that only grow: a gather fills their first entries and keeps the counts, so
  // that reading a patch allocates nothing once the largest patch has been seen.
  template <class T> static void grow(std::vector<T>& v, std::size_t n) {
    if (v.size() < n) v.resize(std::max(n, 2 * v.size()));
  }
  std::vector<VH> ring_;   // a's ring then b's, in rotation order
  std::vector<int> local_; // the same as local numbers
  std::vector<int> hits_;  // the link vertices whose new edge may cross an old one
  std::vector<Vec3> points_;
  std::vector<double> tolerances_;
  std::vector<Point2> framed_;    // the patch in the frame (u, v, n), from a (c's entry: a's)
  std::vector<Point2> projected_; // the same from c
  std::vector<std::array<int, 3>> old_triangles_;
  std::vector<std::array<int, 3>> new_triangles_;
  std::vector<std::array<int, 2>> old_edges_; // interior edges of the old patch (at a or b)
  std::vector<int> fan_next_;                 // per link vertex, the next one counter-clockwise around c
  std::size_t n_points_ = 0, n_old_ = 0, n_new_ = 0, n_edges_ = 0;
  // The gathered patch: a and b with their bounds, whether either is on the surface's boundary,
  // and the patch's vector area with the frame (u, v, n) of the projection.
  Vec3 a_{}, b_{};
  double da_ = 0.0, db_ = 0.0;
  bool boundary_ = true;
  double area_length_ = 0.0;
  Vec3 u_{}, v_{}, n_{};
};

} // namespace geotandem::tandem::detail
