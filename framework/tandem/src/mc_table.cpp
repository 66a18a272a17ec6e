// Generation of the marching-cubes case table from the face rule.
//
// 1. Face segments. Each of the 6 faces, looked at from outside the cell with its corners in
//    counter-clockwise order, gets one segment per run of inside corners: from the crossed edge
//    where the walk enters the run to the crossed edge where it leaves it. An ambiguous face
//    (inside corners on one diagonal only) therefore has its two inside corners cut off
//    separately: "inside corners of an ambiguous face are separated". The rule reads the face's
//    four corner signs only, so the two cells sharing a face draw the same segments on it, in
//    opposite directions (each sees the face from its own outside).
// 2. Loops. A crossed edge lies on two faces of the cell; walked counter-clockwise from outside,
//    the two faces run along it in opposite directions, so one face's segment ends on it and the
//    other's starts: the directed segments chain into closed loops, each crossed edge on one loop.
// 3. Triangulation. Each loop is triangulated as a disc. A diagonal between two vertices whose
//    edges lie on a common face of the cell is forbidden: the neighbour across that face could
//    draw the same diagonal, giving an edge with four triangles. Among the allowed
//    triangulations the one with the shortest total diagonal length (vertices at edge midpoints)
//    is kept. Quadrilaterals are left to run time (shorter diagonal with the real positions):
//    their two diagonals never join vertices of a common face, because consecutive loop sides
//    lie on different faces.
// 4. Orientation. The single-corner case fixes the sign once, so that triangles are
//    counter-clockwise seen from outside (value < iso) and closed bodies have positive volume.

#include "mc_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace geotandem::tandem::detail {

namespace {

struct Vec {
  double x, y, z;
};

Vec operator-(Vec a, Vec b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Vec cross(Vec a, Vec b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(Vec a, Vec b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

// The two axes other than `axis`, lower first.
std::array<int, 2> other_axes(int axis) {
  if (axis == 0) return {1, 2};
  if (axis == 1) return {0, 2};
  return {0, 1};
}

int edge_between(int a, int b) {
  const int diff = a ^ b;
  const int axis = diff == 1 ? 0 : diff == 2 ? 1 : 2;
  const int start = a < b ? a : b;
  const auto o = other_axes(axis);
  return 4 * axis + (((start >> o[0]) & 1) | (((start >> o[1]) & 1) << 1));
}

Vec edge_midpoint(int edge) {
  const int a = edge_start_corner(edge), b = edge_end_corner(edge);
  return {0.5 * ((a & 1) + (b & 1)), 0.5 * (((a >> 1) & 1) + ((b >> 1) & 1)), 0.5 * (((a >> 2) & 1) + ((b >> 2) & 1))};
}

// Faces f = 2 * axis + side hold the corners whose `axis` offset is `side`.
int face_bits(int edge) {
  const int start = edge_start_corner(edge);
  const auto o = other_axes(edge_axis(edge));
  return (1 << (2 * o[0] + ((start >> o[0]) & 1))) | (1 << (2 * o[1] + ((start >> o[1]) & 1)));
}

bool share_face(int e1, int e2) {
  return (face_bits(e1) & face_bits(e2)) != 0;
}

// Corners of face (axis, side) counter-clockwise seen from outside the cell.
std::array<int, 4> face_corners(int axis, int side) {
  const int p = (axis + 1) % 3, q = (axis + 2) % 3; // e_p x e_q = e_axis
  const int dp[4] = {0, 1, 1, 0}, dq[4] = {0, 0, 1, 1};
  std::array<int, 4> out{};
  for (int m = 0; m < 4; ++m)
    out[m] = (side << axis) | (dp[m] << p) | (dq[m] << q);
  if (side == 0) std::swap(out[1], out[3]); // seen from -axis the same cycle runs clockwise
  return out;
}

std::vector<std::vector<int>> loops_of(int case_index) {
  std::array<int, kCellEdges> next{};
  next.fill(-1);
  auto inside = [case_index](int corner) { return ((case_index >> corner) & 1) != 0; };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const auto q = face_corners(axis, side);
      for (int m = 0; m < 4; ++m) {
        if (!inside(q[m]) || inside(q[(m + 1) % 4])) continue; // not where a run of inside corners ends
        int l = m;
        while (inside(q[l]))
          l = (l + 3) % 4; // back to the outside corner before the run
        const int from = edge_between(q[l], q[(l + 1) % 4]);
        const int to = edge_between(q[m], q[(m + 1) % 4]);
        if (next[from] != -1) throw std::logic_error("marching cubes table: two segments leave one edge");
        next[from] = to;
      }
    }
  std::vector<std::vector<int>> loops;
  std::array<bool, kCellEdges> seen{};
  for (int e = 0; e < kCellEdges; ++e) {
    const bool crossed = inside(edge_start_corner(e)) != inside(edge_end_corner(e));
    if (crossed != (next[e] != -1)) throw std::logic_error("marching cubes table: crossed edge without a segment");
    if (!crossed || seen[e]) continue;
    std::vector<int> loop;
    for (int x = e; !seen[x]; x = next[x]) {
      seen[x] = true;
      loop.push_back(x);
    }
    if (loop.front() != next[loop.back()]) throw std::logic_error("marching cubes table: open loop");
    loops.push_back(std::move(loop));
  }
  return loops;
}

// Minimum total diagonal length triangulation of a loop, forbidden diagonals excluded.
std::vector<std::array<int, 3>> triangulate(const std::vector<int>& loop) {
  const int n = static_cast<int>(loop.size());
  constexpr double inf = std::numeric_limits<double>::infinity();
  auto weight = [&](int a, int b) {
    if (b == a + 1 || (a == 0 && b == n - 1)) return 0.0; // a side of the loop
    if (share_face(loop[a], loop[b])) return inf;
    const Vec d = edge_midpoint(loop[a]) - edge_midpoint(loop[b]);
    return std::sqrt(dot(d, d));
  };
  std::vector<std::vector<double>> cost(n, std::vector<double>(n, 0.0));
  std::vector<std::vector<int>> split(n, std::vector<int>(n, -1));
  for (int len = 2; len < n; ++len)
    for (int a = 0; a + len < n; ++a) {
      const int b = a + len;
      cost[a][b] = inf;
      for (int k = a + 1; k < b; ++k) {
        const double c = cost[a][k] + cost[k][b] + weight(a, k) + weight(k, b);
        if (c < cost[a][b]) {
          cost[a][b] = c;
          split[a][b] = k;
        }
      }
    }
  if (!(cost[0][n - 1] < inf)) throw std::logic_error("marching cubes table: loop without an allowed triangulation");
  std::vector<std::array<int, 3>> out;
  std::vector<std::array<int, 2>> todo{{0, n - 1}};
  while (!todo.empty()) {
    const auto [a, b] = todo.back();
    todo.pop_back();
    if (b - a < 2) continue;
    const int k = split[a][b];
    out.push_back({loop[a], loop[k], loop[b]});
    todo.push_back({a, k});
    todo.push_back({k, b});
  }
  return out;
}

std::array<McCase, 256> build() {
  // Orientation from the single-corner case: the triangle must face away from corner 0.
  const auto probe = loops_of(1).front();
  const Vec a = edge_midpoint(probe[0]), b = edge_midpoint(probe[1]), c = edge_midpoint(probe[2]);
  const bool reverse = dot(cross(b - a, c - a), Vec{1, 1, 1}) < 0;

  std::array<McCase, 256> cases{};
  for (int index = 0; index < 256; ++index) {
    McCase& out = cases[index];
    for (int e = 0; e < kCellEdges; ++e)
      if (((index >> edge_start_corner(e)) & 1) != ((index >> edge_end_corner(e)) & 1))
        out.edges[out.edge_count++] = static_cast<std::uint8_t>(e);
    for (auto loop : loops_of(index)) {
      if (reverse) std::reverse(loop.begin() + 1, loop.end());
      ++out.polygon_count;
      if (loop.size() == 4) {
        if (out.quad_count == out.quads.size()) throw std::logic_error("marching cubes table: too many quadrilaterals");
        for (int m = 0; m < 4; ++m)
          out.quads[out.quad_count][m] = static_cast<std::uint8_t>(loop[m]);
        ++out.quad_count;
        continue;
      }
      for (const auto& t : triangulate(loop)) {
        if (out.triangle_count == out.triangles.size())
          throw std::logic_error("marching cubes table: too many triangles");
        for (int m = 0; m < 3; ++m)
          out.triangles[out.triangle_count][m] = static_cast<std::uint8_t>(t[m]);
        ++out.triangle_count;
      }
    }
  }
  return cases;
}

} // namespace

int edge_axis(int edge) {
  return edge / 4;
}

int edge_start_corner(int edge) {
  const int axis = edge / 4, m = edge % 4;
  const auto o = other_axes(axis);
  return ((m & 1) << o[0]) | ((m >> 1) << o[1]);
}

int edge_end_corner(int edge) {
  return edge_start_corner(edge) | (1 << edge_axis(edge));
}

const std::array<McCase, 256>& mc_cases() {
  static const std::array<McCase, 256> cases = build();
  return cases;
}

} // namespace geotandem::tandem::detail
