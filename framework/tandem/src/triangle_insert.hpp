#pragma once
// Appending a triangle to the working mesh, written against HalfedgeMesh's halfedge connectivity like
// the collapse (collapse_ops.hpp): OpenMesh's add_face is general (polygons) and, in Debian's
// build, runs assertions on every link; it was the largest single cost of adding a layer.
//
// Triangles may arrive in any order; a vertex may meanwhile carry several separate fans. When a
// triangle joins two fans that are not neighbours around a vertex, the fans between them move to
// another gap of that vertex, so any order of the triangles of a 2-manifold goes in.

#include "working_mesh.hpp"

namespace geotandem::tandem::detail {

// Adds (v0, v1, v2), counter-clockwise seen from outside. Returns an invalid handle when the
// triangle would make the surface non-manifold or inconsistently oriented: a corner that is
// interior already, an edge already used in the same direction, or no gap to move fans to (the
// mesh may then have been relinked and must be dropped). Keeps boundary vertices pointing to a
// boundary outgoing halfedge.
// New edges and the face are appended (HalfedgeMesh::new_edge, new_face): callers inserting many
// triangles reserve the room first, which touches no memory until it is used.
FH insert_triangle(HalfedgeMesh& mesh, VH v0, VH v1, VH v2);

} // namespace geotandem::tandem::detail
