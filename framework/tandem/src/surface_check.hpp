#pragma once
// What a decoded working-surface record must satisfy before any engine takes it in (issue 52: a
// record with valid checksums but forged content crashed the merge or merged as garbage). The
// checksum only says the bytes arrived as they were sent; these checks say the sender wrote a
// surface the engine's invariants hold for (the list: docs/algorithm.md, "What a record must
// satisfy"). Linear in the record, apart from a sort of the components' keys and of each vertex's
// few triangles.

#include <string>

#include "surface_state.hpp"

namespace geotandem::tandem::detail {

// "blocks [..] (N blocks)": the region a record claims, short enough for a message (a worker's
// region can hold thousands of blocks).
std::string record_blocks(const Region& region);

// Throws DataError (naming the record's blocks in its context) at the first inconsistency: the
// cube, axis, options or region out of their domain; a count that does not match; a vertex with a
// non-finite or far-away position or quadric, a radius that is not positive, border bits beyond the
// six faces, a component out of range; an original vertex whose lattice id is not an edge or
// border sample of the cube inside the record's blocks, not where that edge or sample is, or the
// same as another vertex's; a component without a vertex, split in pieces, with a repeated key or
// a key above one of its original vertices' ids; a triangle out of range, with a repeated corner
// or joining two components; an edge used twice in one direction (more than two triangles on an
// edge, or two that disagree on the orientation); a vertex whose triangles do not make fans, that
// is closed around other fans, or (past the sweep) on the surface's boundary but neither an
// original vertex on an open face of the region nor on the cube's border (a hole no merge would
// close); a vertex without a triangle that is not listed as isolated; a queued edge that is not an
// edge of the triangles, is listed twice or out of order, idle, with a non-finite key, a candidate
// far away or held back by the front or the open faces, or delayed past the sweep; ids of the last
// layer or isolated vertices that do not name vertices (isolated ones past the sweep).
void check_state(const SurfaceState& s);

} // namespace geotandem::tandem::detail
