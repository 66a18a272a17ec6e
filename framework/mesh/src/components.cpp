// split_components and weld_by_key: re-indexing a surface without changing its triangles.

#include <algorithm>
#include <limits>
#include <numeric>
#include <string>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/topology.hpp"
#include "stars.hpp"
#include "union_find.hpp"

namespace geotandem::mesh {

namespace {
constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
}

std::vector<SurfaceMesh> split_components(const SurfaceMesh& surface) {
  detail::check_indices(surface);
  const std::size_t nv = surface.points.size();
  detail::UnionFind sets(nv);
  std::vector<bool> referenced(nv, false);
  for (const Triangle& t : surface.triangles) {
    sets.unite(t[0], t[1]);
    sets.unite(t[0], t[2]);
    for (std::uint32_t v : t)
      referenced[v] = true;
  }
  // Components are numbered in the order of their smallest vertex, vertices keep their relative
  // order, triangles their order: the split is deterministic and stable.
  std::vector<std::uint32_t> component(nv, none), local(nv, none);
  std::vector<SurfaceMesh> parts;
  for (std::size_t v = 0; v < nv; ++v) {
    if (!referenced[v]) continue;
    const std::uint32_t root = sets.find(static_cast<std::uint32_t>(v));
    if (component[root] == none) {
      component[root] = static_cast<std::uint32_t>(parts.size());
      parts.emplace_back();
    }
    SurfaceMesh& part = parts[component[root]];
    local[v] = static_cast<std::uint32_t>(part.points.size());
    part.points.push_back(surface.points[v]);
  }
  for (const Triangle& t : surface.triangles)
    parts[component[sets.find(t[0])]].triangles.push_back({local[t[0]], local[t[1]], local[t[2]]});
  return parts;
}

SurfaceMesh weld_by_key(const std::vector<Point>& points, const std::vector<std::uint64_t>& keys,
                        const std::vector<Triangle>& triangles) {
  if (keys.size() != points.size())
    throw InvalidArgument("weld_by_key got " + std::to_string(points.size()) + " points but " +
                              std::to_string(keys.size()) + " keys",
                          {}, "give exactly one key per point");
  if (points.size() > none)
    throw InvalidArgument("weld_by_key got " + std::to_string(points.size()) +
                          " points; at most 2^32 - 1 are supported");
  const std::size_t nv = points.size();
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (std::uint32_t v : triangles[t])
      if (v >= nv)
        throw InvalidArgument("triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) +
                              " but there are " + std::to_string(nv) + " points");

  // Sorting the indices by (key, index) gives each key's first point as its representative.
  std::vector<std::uint32_t> order(nv);
  std::iota(order.begin(), order.end(), std::uint32_t{0});
  std::sort(order.begin(), order.end(),
            [&keys](std::uint32_t a, std::uint32_t b) { return keys[a] != keys[b] ? keys[a] < keys[b] : a < b; });
  std::vector<std::uint32_t> representative(nv);
  for (std::size_t a = 0; a < nv;) {
    std::size_t b = a;
    while (b < nv && keys[order[b]] == keys[order[a]])
      representative[order[b++]] = order[a];
    a = b;
  }
  std::vector<std::uint32_t> fresh(nv, none);
  for (const Triangle& t : triangles)
    for (std::uint32_t v : t)
      fresh[representative[v]] = 0;
  SurfaceMesh welded;
  for (std::size_t v = 0; v < nv; ++v)
    if (fresh[v] != none) {
      fresh[v] = static_cast<std::uint32_t>(welded.points.size());
      welded.points.push_back(points[v]);
    }
  welded.triangles.reserve(triangles.size());
  for (const Triangle& t : triangles)
    welded.triangles.push_back({fresh[representative[t[0]]], fresh[representative[t[1]]], fresh[representative[t[2]]]});
  return welded;
}

} // namespace geotandem::mesh
