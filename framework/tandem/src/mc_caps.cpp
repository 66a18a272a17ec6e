// Cap triangles of one square of samples on an outer plane of the cube.
#include "mc_caps.hpp"

#include <utility>

namespace geotandem::tandem::detail {

namespace {

void push_facing(std::uint32_t p, std::uint32_t q, std::uint32_t r, int axis, int side, Layer& out) {
  // Every corner lies on the plane: the normal is along the axis, and never zero (vertices stay
  // kMcVertexMargin away from samples, and the fan below never takes three collinear points).
  const auto& x = out.positions[p];
  const auto& y = out.positions[q];
  const auto& z = out.positions[r];
  const int s = (axis + 1) % 3, t = (axis + 2) % 3;
  const double normal = (y[s] - x[s]) * (z[t] - x[t]) - (y[t] - x[t]) * (z[s] - x[s]);
  if ((normal > 0.0) != (side == 1)) std::swap(q, r);
  out.triangles.push_back({p, q, r});
}

} // namespace

void emit_cap_square(const CapSquare& square, int axis, int side, Layer& out) {
  const auto& in = square.inside;
  const auto& c = square.corner;
  const auto& e = square.edge;
  if (in[0] && in[2] && !in[1] && !in[3]) {
    push_facing(c[0], e[0], e[3], axis, side, out);
    push_facing(c[2], e[2], e[1], axis, side, out);
    return;
  }
  if (in[1] && in[3] && !in[0] && !in[2]) {
    push_facing(c[1], e[1], e[0], axis, side, out);
    push_facing(c[3], e[3], e[2], axis, side, out);
    return;
  }
  // One connected inside part: a convex polygon (the square cut by at most one straight line, or
  // all of it), walked around the square and fanned from its first vertex.
  std::array<std::uint32_t, 6> polygon{};
  int count = 0;
  for (int k = 0; k < 4; ++k) {
    if (in[k]) polygon[count++] = c[k];
    if (in[k] != in[(k + 1) % 4]) polygon[count++] = e[k];
  }
  for (int k = 1; k + 1 < count; ++k)
    push_facing(polygon[0], polygon[k], polygon[k + 1], axis, side, out);
}

} // namespace geotandem::tandem::detail
