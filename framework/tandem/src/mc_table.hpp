#pragma once
// The marching-cubes case table, generated here (never copied) from one face rule. Internal to the
// tandem part; the rule and its consequences are documented in docs/marching-cubes.md.
//
// Cell-local numbering, always in the cube's (i, j, k) frame whatever the extraction axis, so that
// every axis and every block triangulates a cell the same way:
// - corner c sits at (c & 1, (c >> 1) & 1, (c >> 2) & 1);
// - edge e = 4 * axis + m runs along `axis` from the corner whose offsets along the two other axes
//   (lower axis first) are (m & 1, m >> 1);
// - bit c of a case index is set when corner c is inside (value >= iso).

#include <array>
#include <cstdint>

namespace geotandem::tandem::detail {

constexpr int kCellCorners = 8;
constexpr int kCellEdges = 12;

int edge_axis(int edge);
int edge_start_corner(int edge); // the lower-index endpoint
int edge_end_corner(int edge);

// What one case produces. Polygons are closed loops of crossed edges; each is triangulated
// either once here (fixed triangles) or, for quadrilaterals, at run time along the shorter
// diagonal (both diagonals of a quadrilateral are always safe, see mc_table.cpp).
struct McCase {
  std::uint8_t edge_count = 0; // crossed edges
  std::array<std::uint8_t, kCellEdges> edges{};
  std::uint8_t polygon_count = 0;
  std::uint8_t triangle_count = 0; // fixed triangles, corners as edge numbers, counter-clockwise seen from outside
  std::array<std::array<std::uint8_t, 3>, 8> triangles{};
  std::uint8_t quad_count = 0; // quadrilaterals, edge numbers in loop order (same orientation)
  std::array<std::array<std::uint8_t, 4>, 4> quads{};
};

// The 256 cases, built once on first use (thread-safe).
const std::array<McCase, 256>& mc_cases();

} // namespace geotandem::tandem::detail
