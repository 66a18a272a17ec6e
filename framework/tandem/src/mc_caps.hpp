#pragma once
// Caps: the part of a square of samples on one of the cube's outer planes that lies inside
// (value >= iso), as triangles whose corners are the square's inside samples and the vertices on
// its crossed edges. Internal to the tandem part; see docs/caps.md.

#include <array>
#include <cstdint>

#include "geotandem/tandem/layer.hpp"

namespace geotandem::tandem::detail {

// One square, corners in cyclic order. edge[c] joins corner c and corner (c + 1) % 4; it is read
// only where the two corners differ. Vertex numbers index the layer's vertices.
struct CapSquare {
  std::array<bool, 4> inside{};
  std::array<std::uint32_t, 4> corner{};
  std::array<std::uint32_t, 4> edge{};
};

// Appends the square's cap triangles to `out`, facing out of the cube: along `axis`, towards
// lower indices when side is 0, higher when 1. The inside corners of an ambiguous square (two
// inside corners on a diagonal) are separated, as marching cubes separates them on a cell face,
// so the cap's border is exactly the body's border on that plane.
void emit_cap_square(const CapSquare& square, int axis, int side, Layer& out);

} // namespace geotandem::tandem::detail
