// extract_surface: every layer of a block welded into one mesh by lattice-edge id.

#include <unordered_map>

#include "geotandem/tandem/marching_cubes.hpp"

namespace geotandem::tandem {

mesh::SurfaceMesh extract_surface(const volume::Volume& volume, const volume::Box& cells, const McOptions& options,
                                  std::vector<std::uint64_t>* ids) {
  LayerExtractor extractor(volume, cells, options);
  mesh::SurfaceMesh surface;
  std::vector<std::uint64_t> point_ids;
  // Only the cross-section between two consecutive layers is shared. The extractor lists the
  // vertices of cross-section k - 1 first in layer k, in the order layer k - 1 listed them, so
  // welding is a comparison of ids in order; a map is the fallback should that order ever differ.
  std::vector<std::uint64_t> plane_ids;    // ids of the last layer's vertices on its upper cross-section
  std::vector<std::uint32_t> plane_points; // their point numbers
  std::vector<std::uint64_t> next_ids;
  std::vector<std::uint32_t> next_points;
  std::vector<std::uint32_t> remap;
  Layer layer;
  while (extractor.next(layer)) {
    const std::size_t n = layer.vertex_ids.size();
    remap.resize(n);
    std::size_t shared = 0;
    while (shared < plane_ids.size() && shared < n && layer.vertex_ids[shared] == plane_ids[shared]) {
      remap[shared] = plane_points[shared];
      ++shared;
    }
    std::unordered_map<std::uint64_t, std::uint32_t> fallback;
    if (shared < plane_ids.size())
      for (std::size_t i = 0; i < plane_ids.size(); ++i)
        fallback.emplace(plane_ids[i], plane_points[i]);
    next_ids.clear();
    next_points.clear();
    const auto upper = static_cast<double>(layer.rank);
    for (std::size_t i = shared; i < n; ++i) {
      const std::uint64_t id = layer.vertex_ids[i];
      const auto found = fallback.empty() ? fallback.end() : fallback.find(id);
      if (found != fallback.end()) {
        remap[i] = found->second;
      } else {
        remap[i] = static_cast<std::uint32_t>(surface.points.size());
        surface.points.push_back(layer.positions[i]);
        point_ids.push_back(id);
      }
      // On the upper cross-section exactly: vertices across the layer stop short of it.
      if (layer.positions[i][static_cast<std::size_t>(layer.axis)] == upper) {
        next_ids.push_back(id);
        next_points.push_back(remap[i]);
      }
    }
    for (const auto& t : layer.triangles)
      surface.triangles.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});
    std::swap(plane_ids, next_ids);
    std::swap(plane_points, next_points);
  }
  if (ids) *ids = std::move(point_ids);
  return surface;
}

} // namespace geotandem::tandem
