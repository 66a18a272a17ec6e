#include "surface_storage.hpp"

#include <algorithm>
#include <utility>

#include "spare_meshes.hpp"
#include "triangle_insert.hpp"

namespace geotandem::tandem::detail {

SurfaceStorage::SurfaceStorage(const std::array<double, 3>& cube_hi) : mesh_(take_spare_mesh()), cube_hi_(cube_hi) {}

SurfaceStorage::~SurfaceStorage() = default;

void SurfaceStorage::give_back_room(bool leaf) noexcept {
  keep_spare_mesh(std::move(mesh_), leaf);
}

std::uint8_t SurfaceStorage::border_bits(const std::array<double, 3>& p) const {
  std::uint8_t bits = 0;
  for (unsigned i = 0; i < 3; ++i) {
    if (p[i] == 0.0) bits |= static_cast<std::uint8_t>(1u << (2 * i));
    if (p[i] == cube_hi_[i]) bits |= static_cast<std::uint8_t>(2u << (2 * i));
  }
  return bits;
}

void SurfaceStorage::make_room(std::size_t nv, std::size_t ne, std::size_t nf) {
  const std::size_t v = mesh_->vertex_capacity(), e = mesh_->edge_capacity(), f = mesh_->face_capacity();
  const auto room = [](std::size_t need, std::size_t have) {
    return need <= have ? have : std::max(need, have + have / 4);
  };
  if (nv > v || ne > e || nf > f) mesh_->reserve(room(nv, v), room(ne, e), room(nf, f));
}

std::size_t SurfaceStorage::begin_append(std::size_t new_vertices, std::size_t triangles, bool exact) {
  append_vertices_ = mesh_->n_vertices();
  append_edges_ = mesh_->n_edges();
  append_faces_ = mesh_->n_faces();
  const std::size_t nv = append_vertices_ + new_vertices, ne = append_edges_ + 3 * triangles,
                    nf = append_faces_ + triangles;
  // Edges and faces are appended as the triangles go in: only the room they use is touched.
  if (exact)
    mesh_->reserve(nv, ne, nf);
  else
    make_room(nv, ne, nf);
  mesh_->resize(nv, append_edges_, append_faces_);
  return append_vertices_;
}

FH SurfaceStorage::add_triangle(VH a, VH b, VH c) {
  return insert_triangle(*mesh_, a, b, c);
}

void SurfaceStorage::end_append() {
  EdgeRecord* edges = mesh_->edge_records();
  for (std::size_t i = append_edges_; i < mesh_->n_edges(); ++i) {
    edges[i] = EdgeRecord{};
    edges[i].alive = true;
  }
  live_vertices_ += mesh_->n_vertices() - append_vertices_;
  live_faces_ += mesh_->n_faces() - append_faces_;
  append_vertices_ = mesh_->n_vertices();
  append_edges_ = mesh_->n_edges();
  append_faces_ = mesh_->n_faces();
}

void SurfaceStorage::compact(bool give_back) {
  const std::vector<std::int32_t> moved = mesh_->compact(give_back);
  auto remap = [&](std::int32_t& v) { v = v >= 0 ? moved[static_cast<std::size_t>(v)] : -1; };
  previous_ids_.for_each([&](std::uint64_t, std::int32_t& v) { remap(v); });
  current_ids_.for_each([&](std::uint64_t, std::int32_t& v) { remap(v); });
  std::vector<std::int32_t> isolated;
  for (std::int32_t v : isolated_) {
    remap(v);
    if (v >= 0) isolated.push_back(v);
  }
  isolated_.swap(isolated);

  // Components: renumber the live ones and pick members again.
  const std::vector<std::int32_t> renumber = components_.compact();
  for (std::size_t i = 0; i < components_.record_count(); ++i)
    components_.at(static_cast<std::int32_t>(i)).member = -1;
  VertexRecord* vertices = mesh_->vertex_records();
  for (std::size_t i = 0; i < mesh_->n_vertices(); ++i) {
    VertexRecord& r = vertices[i];
    r.component = renumber[static_cast<std::size_t>(r.component)];
    ComponentRecord& c = components_.at(r.component);
    if (c.member < 0) c.member = static_cast<std::int32_t>(i);
  }
  append_vertices_ = mesh_->n_vertices();
  append_edges_ = mesh_->n_edges();
  append_faces_ = mesh_->n_faces();
}

void SurfaceStorage::drop_isolated_vertices() {
  for (std::int32_t i : isolated_) {
    const VH v(i);
    VertexRecord& r = vertex(v);
    if (!r.alive || !mesh_->is_isolated(v)) continue;
    components_.remove(components_.find(r.component));
    r.alive = false;
    --live_vertices_;
  }
  isolated_.clear();
}

mesh::SurfaceMesh SurfaceStorage::snapshot() const {
  mesh::SurfaceMesh out;
  std::vector<std::int32_t> index(mesh_->n_vertices(), -1);
  for (std::size_t i = 0; i < mesh_->n_vertices(); ++i) {
    if (!mesh_->vertex_records()[i].alive) continue;
    index[i] = static_cast<std::int32_t>(out.points.size());
    out.points.push_back(to_vec(mesh_->points()[i]));
  }
  const auto number = [&](VH v) { return static_cast<std::uint32_t>(index[static_cast<std::size_t>(v.idx())]); };
  for (std::size_t i = 0; i < mesh_->n_faces(); ++i) {
    if (!mesh_->face_records()[i].alive) continue;
    const HH h = mesh_->halfedge_handle(FH(static_cast<int>(i)));
    out.triangles.push_back({number(mesh_->from_vertex_handle(h)), number(mesh_->to_vertex_handle(h)),
                             number(mesh_->to_vertex_handle(mesh_->next_halfedge_handle(h)))});
  }
  return out;
}

} // namespace geotandem::tandem::detail
