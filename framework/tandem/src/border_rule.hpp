#pragma once
// Which collapses the cube's border allows (docs/caps.md). A vertex on outer faces of the cube
// carries their bits (bit 2 * axis + side, VertexRecord::border) and keeps its coordinates on
// them, so caps stay on their planes and vertices on a cube edge stay on that edge. The vertex a
// collapse makes lies on every face of both ends; the rule refuses a collapse that would put it on
// faces that neither end lies on all of (a cap vertex of one face and one of another face would
// otherwise meet on the edge or the corner between them, far from both), or on both faces of one
// axis (a cube one sample thick).

namespace geotandem::tandem::detail {

inline bool border_allows_collapse(unsigned border_a, unsigned border_b) {
  const unsigned both = border_a | border_b;
  if (both & (both >> 1) & 0b010101u) return false;
  return both == border_a || both == border_b;
}

} // namespace geotandem::tandem::detail
