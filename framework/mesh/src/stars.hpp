#pragma once
// Vertex stars: the triangles around each vertex in compressed rows, and a walk over every vertex
// star that reports each undirected edge once and the number of fans around each vertex. All
// topology and border checks of the part are built on it: it needs two flat arrays and a counting
// sort, no map of vertex pairs, so it stays linear in the size of the surface.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geotandem/mesh/surface.hpp"

namespace geotandem::mesh::detail {

// True when a triangle repeats a vertex index: such a triangle has no proper edges and is left
// out of every star.
inline bool repeats_index(const Triangle& t) {
  return t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
}

struct VertexStars {
  std::vector<std::size_t> offsets;     // vertex_count + 1 entries
  std::vector<std::uint32_t> triangles; // triangle ids, grouped by vertex, ascending within a row
};

// Throws InvalidArgument when a triangle refers to a vertex that does not exist.
void check_indices(const SurfaceMesh& surface);

// Builds the stars of `surface`. Throws InvalidArgument when a triangle refers to a vertex that
// does not exist or when there are more than 2^32 - 1 triangles.
VertexStars build_vertex_stars(const SurfaceMesh& surface);

// One undirected edge {v, w}, reported at its smaller endpoint v.
struct EdgeVisit {
  std::uint32_t v = 0;
  std::uint32_t w = 0;
  std::uint32_t count = 0;  // triangles that hold the edge
  bool misoriented = false; // two triangles that run the edge in the same direction
};

// Calls on_edge(const EdgeVisit&) once per undirected edge and on_vertex(v, fans, star_size) once
// per vertex with a non-empty star. `fans` is the number of groups of triangles around v that are
// connected through edges of v held by exactly two triangles: 1 for a disc or half-disc.
template <class EdgeFn, class VertexFn>
void walk_stars(const SurfaceMesh& surface, const VertexStars& stars, EdgeFn&& on_edge, VertexFn&& on_vertex) {
  struct Spoke {
    std::uint32_t w;     // the other endpoint
    std::uint32_t local; // the triangle's position in the star
    bool outgoing;       // the triangle runs v -> w
  };
  std::vector<Spoke> spokes;
  std::vector<std::uint32_t> parent;
  auto find = [&parent](std::uint32_t x) {
    while (parent[x] != x)
      x = parent[x] = parent[parent[x]];
    return x;
  };
  const std::size_t n = stars.offsets.size() - 1;
  for (std::size_t vi = 0; vi < n; ++vi) {
    const std::size_t begin = stars.offsets[vi], end = stars.offsets[vi + 1];
    if (begin == end) continue;
    const auto v = static_cast<std::uint32_t>(vi);
    const auto m = static_cast<std::uint32_t>(end - begin);
    spokes.clear();
    parent.resize(m);
    for (std::uint32_t l = 0; l < m; ++l) {
      parent[l] = l;
      const Triangle& t = surface.triangles[stars.triangles[begin + l]];
      const int p = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
      spokes.push_back({t[(p + 1) % 3], l, true});
      spokes.push_back({t[(p + 2) % 3], l, false});
    }
    std::sort(spokes.begin(), spokes.end(), [](const Spoke& a, const Spoke& b) { return a.w < b.w; });
    std::uint32_t fans = m;
    for (std::size_t a = 0; a < spokes.size();) {
      std::size_t b = a + 1;
      while (b < spokes.size() && spokes[b].w == spokes[a].w)
        ++b;
      const auto count = static_cast<std::uint32_t>(b - a);
      if (count == 2) {
        const std::uint32_t ra = find(spokes[a].local), rb = find(spokes[a + 1].local);
        if (ra != rb) {
          parent[ra] = rb;
          --fans;
        }
      }
      if (spokes[a].w > v)
        on_edge(EdgeVisit{v, spokes[a].w, count, count == 2 && spokes[a].outgoing == spokes[a + 1].outgoing});
      a = b;
    }
    on_vertex(v, fans, m);
  }
}

} // namespace geotandem::mesh::detail
