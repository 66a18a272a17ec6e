#pragma once
// The topological side of a collapse, written against HalfedgeMesh's halfedge connectivity directly:
// the link condition, the flip/degeneracy test and the collapse itself. Measured while choosing
// the design (ALGORITHM.md): twice as fast as OpenMesh's is_collapse_ok + collapse, which Debian
// builds with assertions and which touch status bits we do not keep on halfedges.
//
// Conventions: a collapse is given by a halfedge h from a to b; a is removed, b is kept (and moved
// to c by the caller). Boundary vertices keep a boundary halfedge as their outgoing halfedge
// (OpenMesh's invariant), which is what is_boundary(vertex) relies on.

#include <algorithm>
#include <cstdint>
#include <vector>

#include "working_mesh.hpp"

namespace geotandem::tandem::detail {

// Per-vertex marks for neighbourhood tests, reset by bumping a stamp.
class VertexMarks {
public:
  void ensure(std::size_t n) {
    if (marks_.size() < n) marks_.resize(n, 0);
  }
  std::uint32_t next_stamp() {
    if (++stamp_ == 0) { // wrapped: forget every old mark
      std::fill(marks_.begin(), marks_.end(), 0u);
      stamp_ = 1;
    }
    return stamp_;
  }
  void mark(VH v, std::uint32_t stamp) { marks_[static_cast<std::size_t>(v.idx())] = stamp; }
  bool marked(VH v, std::uint32_t stamp) const { return marks_[static_cast<std::size_t>(v.idx())] == stamp; }
  // Forgets every mark and gives the storage back.
  void clear() {
    std::vector<std::uint32_t>().swap(marks_);
    stamp_ = 0;
  }

private:
  std::vector<std::uint32_t> marks_;
  std::uint32_t stamp_ = 0;
};

// Whether collapsing h keeps the surface a 2-manifold of the same topology: the link condition
// (the common neighbours of a and b are exactly the vertices opposite ab), no interior edge
// between two boundary vertices, no triangle left dangling, no tetrahedron collapsed.
bool link_condition_ok(const HalfedgeMesh& mesh, HH h, VertexMarks& marks);

// Whether moving a and b to c leaves every surviving triangle around them non-degenerate and
// turned by less than acos(min_cosine) from its old orientation. `points` are the mesh's points.
bool collapse_keeps_shape(const HalfedgeMesh& mesh, HH h, const Vec3& c, const HalfedgeMesh::Point* points);

// Removes a and the edge ab, merges the two pairs of edges of the triangles abx and aby, deletes
// what disappears (its record is no longer alive) and lists it. Precondition: link_condition_ok(h).
struct CollapseResult {
  VH removed_vertex;
  VH kept_vertex;
  EH removed_edges[3];
  int removed_edge_count = 0;
  FH removed_faces[2];
  int removed_face_count = 0;
};
CollapseResult collapse_halfedge(HalfedgeMesh& mesh, HH h);

// Makes a boundary vertex point to one of its boundary outgoing halfedges.
void adjust_outgoing_halfedge(HalfedgeMesh& mesh, VH v);

} // namespace geotandem::tandem::detail
