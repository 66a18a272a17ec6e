#pragma once
// The full-resolution marching-cubes surface of a cube split into components, each named by its
// smallest lattice-edge id (the key the tandem gives the same component): the oracle the
// simplified components are compared with.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <vector>

#include "geotandem/mesh/surface.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::tandem::testing_support {

inline std::map<std::uint64_t, mesh::SurfaceMesh> full_components(const volume::Volume& volume, int axis, float iso) {
  std::vector<std::uint64_t> ids;
  const mesh::SurfaceMesh full =
      extract_surface(volume, cube_cells(volume.geometry().shape), McOptions{iso, axis}, &ids);
  std::vector<std::uint32_t> parent(full.points.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x)
      x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const mesh::Triangle& t : full.triangles)
    for (int c = 1; c < 3; ++c)
      parent[find(t[static_cast<std::size_t>(c)])] = find(t[0]);
  std::map<std::uint32_t, std::uint64_t> key_of_root;
  for (std::uint32_t p = 0; p < full.points.size(); ++p) {
    auto [it, fresh] = key_of_root.try_emplace(find(p), ids[p]);
    if (!fresh) it->second = std::min(it->second, ids[p]);
  }
  std::map<std::uint64_t, mesh::SurfaceMesh> out;
  std::vector<std::uint32_t> local(full.points.size(), std::numeric_limits<std::uint32_t>::max());
  for (const mesh::Triangle& t : full.triangles) {
    mesh::SurfaceMesh& m = out[key_of_root.at(find(t[0]))];
    mesh::Triangle u{};
    for (std::size_t c = 0; c < 3; ++c) {
      if (local[t[c]] == std::numeric_limits<std::uint32_t>::max()) {
        local[t[c]] = static_cast<std::uint32_t>(m.points.size());
        m.points.push_back(full.points[t[c]]);
      }
      u[c] = local[t[c]];
    }
    m.triangles.push_back(u);
  }
  return out;
}

} // namespace geotandem::tandem::testing_support
