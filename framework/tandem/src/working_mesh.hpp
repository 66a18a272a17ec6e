#pragma once
// The working mesh: OpenMesh's TriMesh (halfedge connectivity, face insertion, garbage collection)
// with double points and status bits only on vertices, edges and faces, plus our records per
// element. The records are OpenMesh properties so that garbage collection permutes them with the
// elements; the hot loops read them through raw pointers refreshed after the mesh grows or is
// compacted (see MeshStore::refresh()).

#include <cstdint>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include "id_map.hpp"
#include "quadric.hpp"

namespace geotandem::tandem::detail {

struct MeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
};
using TriMesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;
using VH = OpenMesh::VertexHandle;
using HH = OpenMesh::HalfedgeHandle;
using EH = OpenMesh::EdgeHandle;
using FH = OpenMesh::FaceHandle;

// Where an edge is: nowhere (rejected or never evaluated), in Q, in W because of the front (time
// lag), or in W because of the open faces (extended time lag). Both W states count for V_w.
enum class EdgeState : std::uint8_t { idle = 0, candidate = 1, delayed = 2, parked = 3 };
inline bool waiting(EdgeState s) {
  return s == EdgeState::delayed || s == EdgeState::parked;
}

struct VertexRecord {
  Quadric shape;       // H_v: sum over the original triangles merged into v of w_t p p^T
  double weight = 0.0; // W_v: their total area
  Isotropy isotropy;   // sum of the isotropy terms of the current triangles around v
  // Volume terms of the current triangles around v (coordinates relative to the surface's origin):
  // sums of their determinants det(p0, p1, p2), of the cross products p x q and the differences
  // q - p of the two corners following v, and of their normals (p1 - p0) x (p2 - p0). With them
  // the volume plane of a collapse costs O(1) (WorkingSurface::Engine::volume_plane).
  double det_sum = 0.0;
  Vec3 cross_sum{0.0, 0.0, 0.0};
  Vec3 link_sum{0.0, 0.0, 0.0};
  Vec3 normal_sum{0.0, 0.0, 0.0};
  double height = 0.0; // time lag: rank at birth, then means
  double rad = 1.0;    // time lag radius
  // The E0 guarantee (collapse_distance.hpp): the distance bound at v, interpolated linearly over
  // the triangles. 0 for an original marching-cubes vertex.
  double tolerance = 0.0;
  std::uint64_t lattice_id = kNoLatticeId; // while the vertex is an original MC vertex
  std::int32_t component = -1;             // any member of its component's union-find class
  // Bit 2 * axis + side: the vertex lies on that face of the cube. This is the collapse loop's
  // constraint hook (Engine::prepare_inputs): c keeps the coordinate of every axis with a bit set,
  // so one bit holds a vertex on a plane, two on a line, three in place; an edge whose ends carry
  // both sides of one axis never collapses. Cap or other constrained vertices set these bits.
  std::uint8_t border = 0;
  // Bumped whenever anything a cost at an edge of v depends on changes: v itself, or a triangle
  // around it (so for c and all its neighbours at each collapse).
  std::uint32_t version = 0;
  bool alive = false;
};

struct EdgeRecord {
  Vec3 target{};    // the candidate c while in Q
  double key = 0.0; // its queue key: eps_alpha in Q, the lag key in W
  // version(a) + version(b) when the candidate was computed: it is stale when they moved on.
  std::uint32_t stamp = 0;
  EdgeState state = EdgeState::idle;
  bool retried = false; // already requeued once at a fallback position
  bool dirty = false;   // kept in Q with an old key although an endpoint changed (lazy evaluation)
  bool alive = false;
};

// A face keeps no terms of its own: its isotropy and volume terms are a function of its corners'
// positions, taken from its first halfedge on (surface_cost.cpp, face_terms()), so computing them
// again gives the same bits that were added to the corners' sums and can be subtracted exactly.
// (Storing them cost 80 bytes per triangle held.)
struct FaceRecord {
  bool alive = false;
};

// One-ring navigation by outgoing halfedges (h goes from v to a neighbour).
inline HH next_outgoing(const TriMesh& m, HH h) {
  return m.next_halfedge_handle(m.opposite_halfedge_handle(h));
}

// The halfedge from `from` to `to`, or an invalid handle when they are not neighbours.
inline HH find_halfedge(const TriMesh& m, VH from, VH to) {
  const HH start = m.halfedge_handle(from);
  if (!start.is_valid()) return HH();
  HH g = start;
  do {
    if (m.to_vertex_handle(g) == to) return g;
    g = next_outgoing(m, g);
  } while (g != start);
  return HH();
}

inline Vec3 to_vec(const TriMesh::Point& p) {
  return {p[0], p[1], p[2]};
}

} // namespace geotandem::tandem::detail
