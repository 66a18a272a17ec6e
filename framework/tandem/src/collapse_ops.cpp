#include "collapse_ops.hpp"

#include <algorithm>
#include <cassert>

namespace geotandem::tandem::detail {
namespace {

// A triangle turned by more than about 78 degrees counts as flipped: the quadrics keep good
// collapses far below this, so the test only stops folds.
constexpr double kMinNormalCosine = 0.2;
// A new triangle whose doubled area is below this fraction of its longest edge squared is a
// sliver (smallest height below 1/1000 of the longest edge): refused.
constexpr double kMinShape = 1e-3;

bool boundary_vertex(const HalfedgeMesh& m, VH v) {
  const HH h = m.halfedge_handle(v);
  return !h.is_valid() || !m.face_handle(h).is_valid();
}

bool boundary_halfedge(const HalfedgeMesh& m, HH h) {
  return !m.face_handle(h).is_valid();
}

Vec3 point(const HalfedgeMesh::Point* p, VH v) {
  const HalfedgeMesh::Point& q = p[v.idx()];
  return {q[0], q[1], q[2]};
}

// Sum of the (area-weighted) normals of the triangles around a and b: the reference direction
// for triangles that are degenerate before the collapse and so have no orientation of their own.
Vec3 patch_normal(const HalfedgeMesh& m, VH a, VH b, const HalfedgeMesh::Point* p) {
  Vec3 sum{0.0, 0.0, 0.0};
  for (VH v : {a, b}) {
    const HH start = m.halfedge_handle(v);
    HH g = start;
    do {
      if (m.face_handle(g).is_valid()) {
        const VH q = m.to_vertex_handle(g), r = m.to_vertex_handle(m.next_halfedge_handle(g));
        const Vec3 pv = point(p, v);
        sum = sum + cross(point(p, q) - pv, point(p, r) - pv);
      }
      g = next_outgoing(m, g);
    } while (g != start);
  }
  return sum;
}

} // namespace

bool link_condition_ok(const HalfedgeMesh& m, HH h, VertexMarks& marks) {
  const HH o = m.opposite_halfedge_handle(h);
  const VH a = m.to_vertex_handle(o), b = m.to_vertex_handle(h);
  const bool has_fh = !boundary_halfedge(m, h), has_fo = !boundary_halfedge(m, o);
  if (!has_fh && !has_fo) return false; // a lone edge: nothing to collapse
  VH x, y;
  if (has_fh) {
    const HH hn = m.next_halfedge_handle(h), hp = m.prev_halfedge_handle(h);
    x = m.to_vertex_handle(hn);
    // Both other edges of abx on the boundary: the collapse would leave a dangling edge.
    if (boundary_halfedge(m, m.opposite_halfedge_handle(hn)) && boundary_halfedge(m, m.opposite_halfedge_handle(hp)))
      return false;
  }
  if (has_fo) {
    const HH on = m.next_halfedge_handle(o), op = m.prev_halfedge_handle(o);
    y = m.to_vertex_handle(on);
    if (boundary_halfedge(m, m.opposite_halfedge_handle(on)) && boundary_halfedge(m, m.opposite_halfedge_handle(op)))
      return false;
  }
  if (has_fh && has_fo) {
    if (x == y) return false;
    // An interior edge between two boundary vertices: the collapse would pinch the boundary.
    if (boundary_vertex(m, a) && boundary_vertex(m, b)) return false;
  }
  // The common neighbours of a and b must be exactly x and y.
  const std::uint32_t stamp = marks.next_stamp();
  int valence_a = 0, valence_b = 0;
  const HH start_a = m.halfedge_handle(a);
  HH g = start_a;
  do {
    marks.mark(m.to_vertex_handle(g), stamp);
    ++valence_a;
    g = next_outgoing(m, g);
  } while (g != start_a);
  const HH start_b = m.halfedge_handle(b);
  g = start_b;
  do {
    const VH v = m.to_vertex_handle(g);
    if (marks.marked(v, stamp) && v != x && v != y) return false;
    ++valence_b;
    g = next_outgoing(m, g);
  } while (g != start_b);
  // Two interior vertices of valence 3 sharing x and y: the component is a tetrahedron.
  if (has_fh && has_fo && valence_a == 3 && valence_b == 3) return false;
  return true;
}

bool collapse_keeps_shape(const HalfedgeMesh& m, HH h, const Vec3& c, const HalfedgeMesh::Point* p) {
  const HH o = m.opposite_halfedge_handle(h);
  const VH a = m.to_vertex_handle(o), b = m.to_vertex_handle(h);
  bool have_reference = false;
  Vec3 reference{};
  for (VH v : {a, b}) {
    const VH other = v == a ? b : a;
    const Vec3 pv = point(p, v);
    const HH start = m.halfedge_handle(v);
    HH g = start;
    do {
      if (m.face_handle(g).is_valid()) {
        const VH q = m.to_vertex_handle(g), r = m.to_vertex_handle(m.next_halfedge_handle(g));
        if (q != other && r != other) { // triangles containing both a and b disappear
          const Vec3 pq = point(p, q), pr = point(p, r);
          const Vec3 n_new = cross(pq - c, pr - c);
          const double longest2 = std::max({norm2(pq - c), norm2(pr - c), norm2(pr - pq)});
          const double n_new2 = norm2(n_new);
          if (!(n_new2 > kMinShape * kMinShape * longest2 * longest2)) return false; // sliver or NaN
          Vec3 n_old = cross(pq - pv, pr - pv);
          const double old_longest2 = std::max({norm2(pq - pv), norm2(pr - pv), norm2(pr - pq)});
          if (!(norm2(n_old) > 1e-12 * old_longest2 * old_longest2)) {
            if (!have_reference) {
              reference = patch_normal(m, a, b, p);
              have_reference = true;
            }
            n_old = reference;
          }
          const double d = dot(n_old, n_new);
          if (!(d > 0.0 && d * d > kMinNormalCosine * kMinNormalCosine * norm2(n_old) * n_new2)) return false;
        }
      }
      g = next_outgoing(m, g);
    } while (g != start);
  }
  return true;
}

namespace {

// The first boundary halfedge out of v in rotation order from its own; invalid when its fan is
// closed.
HH boundary_outgoing(const HalfedgeMesh& m, VH v) {
  const HH start = m.halfedge_handle(v);
  HH g = start;
  do {
    if (boundary_halfedge(m, g)) return g;
    g = next_outgoing(m, g);
  } while (g != start);
  return HH();
}

} // namespace

void adjust_outgoing_halfedge(HalfedgeMesh& m, VH v) {
  const HH g = boundary_outgoing(m, v);
  if (g.is_valid()) m.set_halfedge_handle(v, g);
}

namespace {

// The face of h0 has become a loop of two halfedges h0 (v0 -> v1) and h1 (v1 -> v0): drop the
// edge of h0 and the face, and let h1 take the place of h0's opposite in the neighbouring face.
void collapse_loop(HalfedgeMesh& m, HH h0, CollapseResult& r) {
  const HH h1 = m.next_halfedge_handle(h0);
  assert(m.next_halfedge_handle(h1) == h0);
  const HH o0 = m.opposite_halfedge_handle(h0), o1 = m.opposite_halfedge_handle(h1);
  const VH v0 = m.to_vertex_handle(h1), v1 = m.to_vertex_handle(h0);
  const FH loop_face = m.face_handle(h0);
  const FH g = m.face_handle(o0);
  const HH before = m.prev_halfedge_handle(o0), after = m.next_halfedge_handle(o0);
  m.set_next_halfedge_handle(before, h1);
  m.set_next_halfedge_handle(h1, after);
  if (g.is_valid()) {
    m.set_face_handle(h1, g);
    if (m.halfedge_handle(g) == o0) m.set_halfedge_handle(g, h1);
  } else {
    m.set_boundary(h1);
  }
  if (m.halfedge_handle(v0) == h0) m.set_halfedge_handle(v0, o1);
  if (m.halfedge_handle(v1) == o0) m.set_halfedge_handle(v1, h1);
  const EH dead_edge = m.edge_handle(h0);
  m.edge_records()[dead_edge.idx()].alive = false;
  m.face_records()[loop_face.idx()].alive = false;
  r.removed_edges[r.removed_edge_count++] = dead_edge;
  r.removed_faces[r.removed_face_count++] = loop_face;
}

} // namespace

CollapseResult collapse_halfedge(HalfedgeMesh& m, HH h) {
  CollapseResult r;
  const HH o = m.opposite_halfedge_handle(h);
  const VH a = m.to_vertex_handle(o), b = m.to_vertex_handle(h);
  const HH hn = m.next_halfedge_handle(h), hp = m.prev_halfedge_handle(h);
  const HH on = m.next_halfedge_handle(o), op = m.prev_halfedge_handle(o);
  const FH fh = m.face_handle(h), fo = m.face_handle(o);
  const VH x = fh.is_valid() ? m.to_vertex_handle(hn) : VH();
  const VH y = fo.is_valid() ? m.to_vertex_handle(on) : VH();
  // A vertex whose fan is closed keeps it closed (c's is when a's and b's are; x and y only lose
  // the triangles of ab): only those at the boundary need their outgoing halfedge looked for.
  const bool c_on_boundary = m.is_boundary(a) || m.is_boundary(b);
  const bool x_on_boundary = x.is_valid() && m.is_boundary(x);
  const bool y_on_boundary = y.is_valid() && m.is_boundary(y);

  // Every halfedge that ended at a now ends at b.
  const HH start = m.halfedge_handle(a);
  HH g = start;
  do {
    m.set_vertex_handle(m.opposite_halfedge_handle(g), b);
    g = next_outgoing(m, g);
  } while (g != start);

  // Unlink ab from its two loops.
  m.set_next_halfedge_handle(hp, hn);
  m.set_next_halfedge_handle(op, on);
  if (fh.is_valid()) m.set_halfedge_handle(fh, hn);
  if (fo.is_valid()) m.set_halfedge_handle(fo, on);
  if (m.halfedge_handle(b) == o) m.set_halfedge_handle(b, hn);
  m.set_isolated(a);
  m.vertex_records()[a.idx()].alive = false;
  const EH ab = m.edge_handle(h);
  m.edge_records()[ab.idx()].alive = false;
  r.removed_vertex = a;
  r.kept_vertex = b;
  r.removed_edges[r.removed_edge_count++] = ab;

  // The triangles abx and aby are now loops of two halfedges.
  if (fh.is_valid()) collapse_loop(m, hn, r);
  if (fo.is_valid()) collapse_loop(m, on, r);

  if (c_on_boundary) adjust_outgoing_halfedge(m, b);
  if (x_on_boundary) adjust_outgoing_halfedge(m, x);
  if (y_on_boundary) adjust_outgoing_halfedge(m, y);
  assert(c_on_boundary || !boundary_outgoing(m, b).is_valid());
  assert(x_on_boundary || !x.is_valid() || !boundary_outgoing(m, x).is_valid());
  assert(y_on_boundary || !y.is_valid() || !boundary_outgoing(m, y).is_valid());
  return r;
}

} // namespace geotandem::tandem::detail
