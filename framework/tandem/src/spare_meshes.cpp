// The meshes kept per thread for the next surfaces (spare_meshes.hpp).
//
// A worker extracts leaf after leaf, and each leaf's surface would otherwise fault in fresh pages
// and grow its arrays by copies, layer after layer. A worker holds two meshes at a time (its
// surface and the leaf being extracted), hence two spares. A mesh keeps at most the room of the
// largest leaf (one-block surface) destroyed on the thread: a merged surface's mesh is trimmed to
// that, so that what is kept serves a leaf and no more.
#include "spare_meshes.hpp"

#include <algorithm>
#include <array>
#include <new>
#include <vector>

#include "geotandem/tandem/simplify.hpp"

namespace geotandem::tandem {

namespace {
constexpr std::size_t kSpareMeshes = 2;
thread_local bool keep_storage = false;
thread_local std::vector<std::unique_ptr<detail::HalfedgeMesh>> spare_meshes;
thread_local std::array<std::size_t, 3> leaf_room{0, 0, 0}; // vertices, edges, faces

void keep(std::unique_ptr<detail::HalfedgeMesh> mesh, bool leaf) {
  if (leaf)
    leaf_room = {std::max(leaf_room[0], mesh->vertex_capacity()), std::max(leaf_room[1], mesh->edge_capacity()),
                 std::max(leaf_room[2], mesh->face_capacity())};
  mesh->clear();
  mesh->trim(leaf_room[0], leaf_room[1], leaf_room[2]);
  if (mesh->capacity_bytes() == 0) return;
  if (spare_meshes.size() < kSpareMeshes) {
    spare_meshes.push_back(std::move(mesh));
    return;
  }
  // Full: it replaces the smallest spare when it has more room.
  auto smallest = std::min_element(spare_meshes.begin(), spare_meshes.end(), [](const auto& a, const auto& b) {
    return a->capacity_bytes() < b->capacity_bytes();
  });
  if ((*smallest)->capacity_bytes() < mesh->capacity_bytes()) *smallest = std::move(mesh);
}
} // namespace

void keep_surface_storage(bool on) {
  keep_storage = on;
  if (!on) release_surface_storage();
}

void release_surface_storage() {
  std::vector<std::unique_ptr<detail::HalfedgeMesh>>().swap(spare_meshes);
}

namespace detail {

std::unique_ptr<HalfedgeMesh> take_spare_mesh() {
  if (spare_meshes.empty()) return std::make_unique<HalfedgeMesh>();
  std::unique_ptr<HalfedgeMesh> mesh = std::move(spare_meshes.back());
  spare_meshes.pop_back();
  return mesh;
}

void keep_spare_mesh(std::unique_ptr<HalfedgeMesh> mesh, bool leaf) noexcept {
  if (!mesh || !keep_storage) return;
  try {
    keep(std::move(mesh), leaf);
  } catch (const std::bad_alloc&) {
    // No room to keep it: it is freed as without the spares.
  }
}

std::size_t spare_surface_storage_bytes() {
  std::size_t bytes = 0;
  for (const auto& mesh : spare_meshes)
    bytes += mesh->capacity_bytes();
  return bytes;
}

} // namespace detail
} // namespace geotandem::tandem
