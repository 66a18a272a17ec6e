#pragma once
// The working mesh: halfedge connectivity (the layout of OpenMesh's ArrayKernel: edge e owns the
// halfedges 2e and 2e + 1, each with its target vertex, next and previous halfedge and face),
// points, and our records per element, in arrays of our own. OpenMesh stays the mesh type at the
// boundaries (measures, exports, tests) and lends its handle types; the hot loops read the arrays
// through the mesh each time (surface_storage.hpp), so that growth and compaction move nothing
// anyone holds.
//
// Why not OpenMesh's TriMesh, which this replaced: its containers are private, so its storage could
// only be compacted into a second mesh (the whole surface held twice at each compaction) or grown
// by std::vector's copy (twice again); it keeps status words we do not need (12 bytes per
// triangle); and properties go through virtual calls. Here every array is plain data in
// malloc'ed storage: growing and shrinking go through realloc (mremap for large arrays, no copy),
// and compaction moves the live elements down in place.

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include <OpenMesh/Core/Geometry/VectorT.hh>
#include <OpenMesh/Core/Mesh/Handles.hh>

#include "id_map.hpp"
#include "quadric.hpp"

namespace geotandem::tandem::detail {

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
  // H_v: sum over the original triangles merged into v of w_t p p^T, w_t the triangle's area and p
  // its plane (unit normal, offset). The trace of its 3x3 block is W_v, their total area
  // (weight()), which is therefore not kept apart.
  Quadric shape;
  Isotropy isotropy; // sum of the isotropy terms of the current triangles around v
  // Volume terms of the current triangles around v (coordinates relative to the surface's origin):
  // for each triangle (v, p, q), the cross product p x q and the difference q - p of the two
  // corners following v. With them the volume plane of a collapse costs O(1)
  // (EdgeCost::volume_plane, edge_cost.cpp). The triangles' determinants and normals follow from
  // them and v's own position: det(v, p, q) = v.(p x q) and (p - v) x (q - v) = p x q - v x (q - p),
  // so they are not kept either (40 bytes a vertex with W_v).
  Vec3 cross_sum{0.0, 0.0, 0.0};
  Vec3 link_sum{0.0, 0.0, 0.0};
  double height = 0.0; // time lag: rank at birth, then means
  double rad = 1.0;    // time lag radius
  // The E0 guarantee (collapse_distance.hpp): the distance bound at v, interpolated linearly over
  // the triangles. 0 for an original marching-cubes vertex.
  double tolerance = 0.0;
  std::uint64_t lattice_id = kNoLatticeId; // while the vertex is an original MC vertex
  std::int32_t component = -1;             // any member of its component's union-find class
  // Bumped whenever anything a cost at an edge of v depends on changes: v itself, or a triangle
  // around it (so for c and all its neighbours at each collapse).
  std::uint32_t version = 0;
  // Bit 2 * axis + side: the vertex lies on that face of the cube. This is the collapse loop's
  // constraint hook (EdgeCost::inputs, edge_cost.hpp): c keeps the coordinate of every axis with a bit set,
  // so one bit holds a vertex on a plane, two on a line, three in place; an edge whose ends carry
  // both sides of one axis never collapses. Cap or other constrained vertices set these bits.
  std::uint8_t border = 0;
  bool alive = false;

  double weight() const { return shape.m[0] + shape.m[4] + shape.m[7]; }
};
static_assert(sizeof(VertexRecord) == 216, "a vertex record's size is counted in docs/algorithm.md (Memory)");

// What an edge in Q keeps beside its key: nothing else reads it. It lives in the engine's pool
// (EdgeQueues::pending_, edge_queues.hpp), not in the edge record: Q is empty between simplifications,
// so the surface at rest does not pay 24 bytes an edge for it (36 a triangle).
struct Pending {
  Vec3 target{}; // the candidate c
  // version(a) + version(b) when the candidate was computed: it is stale when they moved on.
  std::uint32_t stamp = 0;
  bool retried = false; // already requeued once at a fallback position
  bool dirty = false;   // kept in Q with an old key although an endpoint changed (lazy evaluation)
};

// The engine's Pending entries, by index, with a free list. When the last entry is released every
// index is free again, so the next one starts from the first; release_storage() gives the room back.
class PendingPool {
public:
  Pending& operator[](std::uint32_t i) { return entries_[i]; }
  const Pending& operator[](std::uint32_t i) const { return entries_[i]; }
  std::uint32_t acquire() {
    ++live_;
    if (free_.empty()) {
      entries_.emplace_back();
      return static_cast<std::uint32_t>(entries_.size() - 1);
    }
    const std::uint32_t i = free_.back();
    free_.pop_back();
    return i;
  }
  void release(std::uint32_t i) {
    if (--live_ == 0) {
      entries_.clear();
      free_.clear();
    } else {
      free_.push_back(i);
    }
  }
  // Only while no entry is held.
  void release_storage() {
    if (live_ != 0) return;
    std::vector<Pending>().swap(entries_);
    std::vector<std::uint32_t>().swap(free_);
  }

private:
  std::vector<Pending> entries_;
  std::vector<std::uint32_t> free_;
  std::size_t live_ = 0;
};

// Where the open faces hold a parked edge back: the face its ball reaches (its index in the
// region's list) and the unit square of that face holding the point it reaches (the cells' lower
// corner, 16 bits each of the face's in-plane coordinates). A merge keeps the edge parked without
// reading the mesh when the grown region still has that square open (surface_merge.cpp).
// kUnknownFace / kUnknownSquare: not known, the edge is placed again when the region changes.
inline constexpr std::uint16_t kUnknownFace = 0xffff;
inline constexpr std::uint32_t kUnknownSquare = 0xffffffff;

inline std::uint32_t square_of(const std::array<double, 2>& at) {
  if (!(at[0] >= 0.0 && at[0] < 65535.0 && at[1] >= 0.0 && at[1] < 65535.0)) return kUnknownSquare;
  return static_cast<std::uint32_t>(at[0]) << 16 | static_cast<std::uint32_t>(at[1]);
}
// The lower corner of a known square (the inverse of square_of, to the unit).
inline std::array<double, 2> square_corner(std::uint32_t square) {
  return {static_cast<double>(square >> 16), static_cast<double>(square & 0xffffu)};
}

struct EdgeRecord {
  double key = 0.0; // its queue key: eps_alpha in Q, the lag key in W
  // While in Q: its Pending in the engine's pool. While parked: the square of its face its ball
  // reaches (above). One field for both: an edge is never in both.
  std::uint32_t pending_or_square = 0;
  EdgeState state = EdgeState::idle;
  bool alive = false;
  std::uint16_t face = kUnknownFace; // while parked: the open face holding it back (above)
};
static_assert(sizeof(EdgeRecord) == 16, "an edge record's size is counted in docs/algorithm.md (Memory)");

// A face keeps no terms of its own: its isotropy and volume terms are a function of its corners'
// positions, taken from its first halfedge on (EdgeCost::add_face_terms, edge_cost.cpp), so computing them
// again gives the same bits that were added to the corners' sums and can be subtracted exactly.
// (Storing them cost 80 bytes per triangle held.)
struct FaceRecord {
  bool alive = false;
};

// A growable array of plain data in malloc'ed storage. Growing and shrinking go through realloc,
// which glibc serves with mremap for large blocks: no second copy is held while the array moves.
template <class T> class PodArray {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);

public:
  PodArray() = default;
  PodArray(const PodArray&) = delete;
  PodArray& operator=(const PodArray&) = delete;
  PodArray(PodArray&& other) noexcept { swap(other); }
  PodArray& operator=(PodArray&& other) noexcept {
    PodArray(std::move(other)).swap(*this);
    return *this;
  }
  ~PodArray() { std::free(data_); }

  void swap(PodArray& other) noexcept {
    std::swap(data_, other.data_);
    std::swap(size_, other.size_);
    std::swap(capacity_, other.capacity_);
  }
  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }
  std::size_t capacity() const { return capacity_; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }

  // Room for exactly n elements when there is less.
  void reserve(std::size_t n) {
    if (n > capacity_) reallocate(n);
  }
  // New elements are copies of `fill`; growing past the room grows it by a quarter at least.
  void resize(std::size_t n, const T& fill) {
    if (n > capacity_) reallocate(std::max(n, capacity_ + capacity_ / 4));
    for (std::size_t i = size_; i < n; ++i)
      new (data_ + i) T(fill);
    size_ = n;
  }
  void push_back(const T& value) {
    if (size_ == capacity_) reallocate(capacity_ < 8 ? 8 : 2 * capacity_);
    new (data_ + size_) T(value);
    ++size_;
  }
  // Forgets the elements and keeps the room.
  void clear() { size_ = 0; }
  // Gives back the room beyond n elements (beyond the size when that is more).
  void trim(std::size_t n) {
    if (capacity_ > std::max(n, size_)) reallocate(std::max(n, size_));
  }

private:
  void reallocate(std::size_t n) {
    if (n == 0) {
      std::free(data_);
      data_ = nullptr;
      capacity_ = 0;
      return;
    }
    void* p = std::realloc(data_, n * sizeof(T));
    if (!p) throw std::bad_alloc();
    data_ = static_cast<T*>(p);
    capacity_ = n;
  }

  T* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

// The working mesh (see the top of this file). Its interface is the part of OpenMesh's
// ArrayKernel the engine uses, with the same names and the same meaning, so that connectivity code
// reads like OpenMesh code. An element is deleted when its record is not alive.
class HalfedgeMesh {
public:
  using Point = OpenMesh::Vec3d;

  std::size_t n_vertices() const { return out_.size(); }
  std::size_t n_edges() const { return halfedges_.size() / 2; }
  std::size_t n_halfedges() const { return halfedges_.size(); }
  std::size_t n_faces() const { return face_halfedge_.size(); }
  std::size_t vertex_capacity() const { return out_.capacity(); }
  std::size_t edge_capacity() const { return edges_.capacity(); }
  std::size_t face_capacity() const { return face_halfedge_.capacity(); }

  // Connectivity.
  HH halfedge_handle(VH v) const { return out_[idx(v)]; }
  HH halfedge_handle(FH f) const { return face_halfedge_[idx(f)]; }
  static HH halfedge_handle(EH e, unsigned side) { return HH(2 * e.idx() + static_cast<int>(side)); }
  static HH opposite_halfedge_handle(HH h) { return HH(h.idx() ^ 1); }
  static EH edge_handle(HH h) { return EH(h.idx() >> 1); }
  VH to_vertex_handle(HH h) const { return halfedges_[idx(h)].to; }
  VH from_vertex_handle(HH h) const { return halfedges_[idx(h) ^ 1u].to; }
  HH next_halfedge_handle(HH h) const { return halfedges_[idx(h)].next; }
  HH prev_halfedge_handle(HH h) const { return halfedges_[idx(h)].prev; }
  FH face_handle(HH h) const { return halfedges_[idx(h)].face; }
  bool is_boundary(HH h) const { return !face_handle(h).is_valid(); }
  // No triangle at v, or v on the boundary (its outgoing halfedge is then a boundary one).
  bool is_boundary(VH v) const {
    const HH h = halfedge_handle(v);
    return !h.is_valid() || is_boundary(h);
  }
  bool is_isolated(VH v) const { return !halfedge_handle(v).is_valid(); }

  void set_halfedge_handle(VH v, HH h) { out_[idx(v)] = h; }
  void set_halfedge_handle(FH f, HH h) { face_halfedge_[idx(f)] = h; }
  void set_vertex_handle(HH h, VH v) { halfedges_[idx(h)].to = v; }
  // Sets prev as well, as OpenMesh does.
  void set_next_halfedge_handle(HH h, HH next) {
    halfedges_[idx(h)].next = next;
    halfedges_[idx(next)].prev = h;
  }
  void set_face_handle(HH h, FH f) { halfedges_[idx(h)].face = f; }
  void set_boundary(HH h) { halfedges_[idx(h)].face = FH(); }
  void set_isolated(VH v) { out_[idx(v)] = HH(); }

  // Points and records.
  Point* points() { return points_.data(); }
  const Point* points() const { return points_.data(); }
  const Point& point(VH v) const { return points_[idx(v)]; }
  VertexRecord* vertex_records() { return vertices_.data(); }
  const VertexRecord* vertex_records() const { return vertices_.data(); }
  EdgeRecord* edge_records() { return edges_.data(); }
  const EdgeRecord* edge_records() const { return edges_.data(); }
  FaceRecord* face_records() { return faces_.data(); }
  const FaceRecord* face_records() const { return faces_.data(); }
  bool deleted(VH v) const { return !vertices_[idx(v)].alive; }
  bool deleted(EH e) const { return !edges_[idx(e)].alive; }
  bool deleted(FH f) const { return !faces_[idx(f)].alive; }

  // Single elements, alive (for tests and small meshes; the engine grows by whole layers).
  VH add_vertex(const Point& p);
  HH new_edge(VH from, VH to); // the halfedge from -> to
  FH new_face();

  // New elements are unlinked, at the origin, with default (not alive) records.
  void resize(std::size_t nv, std::size_t ne, std::size_t nf);
  void reserve(std::size_t nv, std::size_t ne, std::size_t nf);
  // Moves the live elements (alive records) down in place, keeping their order, and gives back
  // every byte beyond them when `give_back` (else the room stays for the elements still to come).
  // Returns old -> new vertex index (-1 for a deleted vertex).
  std::vector<std::int32_t> compact(bool give_back);
  // No elements left, the room kept (for a mesh taken over by another surface).
  void clear();
  // Gives back the room beyond nv vertices, ne edges and nf faces.
  void trim(std::size_t nv, std::size_t ne, std::size_t nf);
  // The bytes of room held, used or not.
  std::size_t capacity_bytes() const;

private:
  struct Halfedge {
    VH to;
    HH next;
    HH prev;
    FH face;
  };
  template <class Handle> static std::size_t idx(Handle h) { return static_cast<std::size_t>(h.idx()); }
  // op(array, n) on every array of `mesh` (const or not), n its element count for nv vertices, ne
  // edges and nf faces.
  template <class Mesh, class Op>
  static void for_each_array(Mesh& mesh, std::size_t nv, std::size_t ne, std::size_t nf, Op op) {
    op(mesh.out_, nv);
    op(mesh.points_, nv);
    op(mesh.vertices_, nv);
    op(mesh.halfedges_, 2 * ne);
    op(mesh.edges_, ne);
    op(mesh.face_halfedge_, nf);
    op(mesh.faces_, nf);
  }

  PodArray<HH> out_;                // per vertex: an outgoing halfedge (a boundary one on the boundary)
  PodArray<Point> points_;          // per vertex
  PodArray<VertexRecord> vertices_; // per vertex
  PodArray<Halfedge> halfedges_;    // two per edge
  PodArray<EdgeRecord> edges_;      // per edge
  PodArray<HH> face_halfedge_;      // per face: its first halfedge
  PodArray<FaceRecord> faces_;      // per face
};

// One-ring navigation by outgoing halfedges (h goes from v to a neighbour).
inline HH next_outgoing(const HalfedgeMesh& m, HH h) {
  return m.next_halfedge_handle(m.opposite_halfedge_handle(h));
}

// The halfedge from `from` to `to`, or an invalid handle when they are not neighbours.
inline HH find_halfedge(const HalfedgeMesh& m, VH from, VH to) {
  const HH start = m.halfedge_handle(from);
  if (!start.is_valid()) return HH();
  HH g = start;
  do {
    if (m.to_vertex_handle(g) == to) return g;
    g = next_outgoing(m, g);
  } while (g != start);
  return HH();
}

inline Vec3 to_vec(const HalfedgeMesh::Point& p) {
  return {p[0], p[1], p[2]};
}

} // namespace geotandem::tandem::detail
