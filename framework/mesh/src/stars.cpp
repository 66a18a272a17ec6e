#include "stars.hpp"

#include <limits>
#include <string>

#include "geotandem/core/error.hpp"

namespace geotandem::mesh::detail {

void check_indices(const SurfaceMesh& surface) {
  const std::size_t nv = surface.points.size();
  for (std::size_t t = 0; t < surface.triangles.size(); ++t)
    for (std::uint32_t v : surface.triangles[t])
      if (v >= nv)
        throw InvalidArgument("triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) +
                                  " but the surface has " + std::to_string(nv) + " vertices",
                              {}, "the surface is corrupt: check the code or file that produced it");
}

VertexStars build_vertex_stars(const SurfaceMesh& surface) {
  const std::size_t nv = surface.points.size();
  const std::size_t nt = surface.triangles.size();
  if (nt > std::numeric_limits<std::uint32_t>::max())
    throw InvalidArgument("the surface has " + std::to_string(nt) + " triangles; at most 2^32 - 1 are supported", {},
                          "split the surface into components first");
  check_indices(surface);
  VertexStars stars;
  stars.offsets.assign(nv + 1, 0);
  for (std::size_t t = 0; t < nt; ++t) {
    const Triangle& tri = surface.triangles[t];
    if (repeats_index(tri)) continue;
    for (std::uint32_t v : tri)
      ++stars.offsets[v + 1];
  }
  for (std::size_t v = 0; v < nv; ++v)
    stars.offsets[v + 1] += stars.offsets[v];
  stars.triangles.resize(stars.offsets[nv]);
  std::vector<std::size_t> cursor(stars.offsets.begin(), stars.offsets.end() - 1);
  for (std::size_t t = 0; t < nt; ++t) {
    const Triangle& tri = surface.triangles[t];
    if (repeats_index(tri)) continue;
    for (std::uint32_t v : tri)
      stars.triangles[cursor[v]++] = static_cast<std::uint32_t>(t);
  }
  return stars;
}

} // namespace geotandem::mesh::detail
