#include "triangle_insert.hpp"

#include "collapse_ops.hpp"

namespace geotandem::tandem::detail {
namespace {

bool is_boundary_halfedge(const HalfedgeMesh& m, HH h) {
  return !m.face_handle(h).is_valid();
}

// A vertex can take a new triangle when it has no triangle yet or lies on the boundary.
bool open_vertex(const HalfedgeMesh& m, VH v) {
  const HH h = m.halfedge_handle(v);
  return !h.is_valid() || is_boundary_halfedge(m, h);
}

// Around the vertex where `in` starts, the incoming boundary halfedge that ends the fan beginning
// with the outgoing boundary halfedge `in`.
HH end_of_fan(const HalfedgeMesh& m, HH in) {
  HH g = in;
  for (;;) {
    const HH t = m.opposite_halfedge_handle(g);
    if (is_boundary_halfedge(m, t)) return t;
    g = m.next_halfedge_handle(t);
  }
}

} // namespace

FH insert_triangle(HalfedgeMesh& m, VH v0, VH v1, VH v2) {
  const VH v[3] = {v0, v1, v2};
  // inner[i] goes from v[i] to v[i + 1] and will bound the new triangle.
  HH inner[3];
  bool fresh[3];
  for (int i = 0; i < 3; ++i) {
    if (!open_vertex(m, v[i])) return FH(); // its fan is closed already
    inner[i] = find_halfedge(m, v[i], v[(i + 1) % 3]);
    fresh[i] = !inner[i].is_valid();
    if (!fresh[i] && !is_boundary_halfedge(m, inner[i])) return FH(); // edge used in this direction
  }

  // Two existing edges meeting at a corner must be consecutive in its boundary loop; if fans lie
  // between them, move those fans to the gap that follows the fan of the second edge.
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (fresh[i] || fresh[j]) continue;
    const HH before = inner[i], after = inner[j];
    if (m.next_halfedge_handle(before) == after) continue;
    const HH gap_in = end_of_fan(m, after);
    if (gap_in == before) return FH(); // the triangle would close the vertex around other fans
    const HH gap_out = m.next_halfedge_handle(gap_in);
    const HH patch_first = m.next_halfedge_handle(before);
    const HH patch_last = m.prev_halfedge_handle(after);
    m.set_next_halfedge_handle(gap_in, patch_first);
    m.set_next_halfedge_handle(patch_last, gap_out);
    m.set_next_halfedge_handle(before, after);
  }

  for (int i = 0; i < 3; ++i)
    if (fresh[i]) inner[i] = m.new_edge(v[i], v[(i + 1) % 3]);

  // Links to make, collected first: each reads the boundary loops as they were.
  HH link_from[9], link_to[9];
  int links = 0;
  auto link = [&](HH a, HH b) {
    link_from[links] = a;
    link_to[links] = b;
    ++links;
  };
  VH isolated_corner[3];
  HH isolated_out[3];
  int isolated = 0;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const VH corner = v[j];
    const HH before = inner[i], after = inner[j];
    const HH outer_in = m.opposite_halfedge_handle(after);   // ends at the corner, outside the triangle
    const HH outer_out = m.opposite_halfedge_handle(before); // starts at the corner, outside
    if (fresh[i] && fresh[j]) {
      const HH out = m.halfedge_handle(corner);
      if (!out.is_valid()) { // a new vertex: the two outer halfedges make its boundary loop
        link(outer_in, outer_out);
        isolated_corner[isolated] = corner;
        isolated_out[isolated++] = outer_out;
      } else { // a new wedge in the gap the vertex points to
        link(m.prev_halfedge_handle(out), outer_out);
        link(outer_in, out);
      }
    } else if (!fresh[i] && fresh[j]) {
      link(outer_in, m.next_halfedge_handle(before));
    } else if (fresh[i] && !fresh[j]) {
      link(m.prev_halfedge_handle(after), outer_out);
    }
    link(before, after);
  }
  for (int k = 0; k < links; ++k)
    m.set_next_halfedge_handle(link_from[k], link_to[k]);
  for (int k = 0; k < isolated; ++k)
    m.set_halfedge_handle(isolated_corner[k], isolated_out[k]);

  const FH f = m.new_face();
  m.set_halfedge_handle(f, inner[0]);
  for (int i = 0; i < 3; ++i)
    m.set_face_handle(inner[i], f);
  for (int i = 0; i < 3; ++i)
    adjust_outgoing_halfedge(m, v[i]);
  return f;
}

} // namespace geotandem::tandem::detail
