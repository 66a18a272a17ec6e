#pragma once
// The working surface's storage: the halfedge mesh with its records and points, the component
// table, and the ids that weld a layer to the one before it. It grows, compacts, and takes in new
// elements by one bulk path (a layer, the other side of a merge, an imported state: see
// begin_append()). What is done with the records (queues, cost, bound, collapses) belongs to the
// collapser (collapser.hpp); the engine (surface_engine.hpp) drives both.
//
// Records are read through the mesh each time (vertex(), edge(), face(), position()): nothing
// keeps a pointer into storage that growth or compaction would move.

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "component_table.hpp"
#include "geotandem/mesh/surface.hpp"
#include "id_map.hpp"
#include "working_mesh.hpp"

namespace geotandem::tandem::detail {

class SurfaceStorage {
public:
  // Takes the room a surface destroyed on this thread left (spare_meshes.hpp). `cube_hi`: the
  // cube's last sample index on each axis (border_bits()).
  explicit SurfaceStorage(const std::array<double, 3>& cube_hi);
  // Gives the mesh's room back to the thread for the next surface; `leaf`: the surface was one
  // block's (spare_meshes.hpp keeps those).
  void give_back_room(bool leaf) noexcept;
  ~SurfaceStorage();
  SurfaceStorage(const SurfaceStorage&) = delete;
  SurfaceStorage& operator=(const SurfaceStorage&) = delete;

  HalfedgeMesh& mesh() { return *mesh_; }
  const HalfedgeMesh& mesh() const { return *mesh_; }
  VertexRecord& vertex(VH v) { return mesh_->vertex_records()[v.idx()]; }
  const VertexRecord& vertex(VH v) const { return mesh_->vertex_records()[v.idx()]; }
  EdgeRecord& edge(EH e) { return mesh_->edge_records()[e.idx()]; }
  const EdgeRecord& edge(EH e) const { return mesh_->edge_records()[e.idx()]; }
  FaceRecord& face(FH f) { return mesh_->face_records()[f.idx()]; }
  const FaceRecord& face(FH f) const { return mesh_->face_records()[f.idx()]; }
  Vec3 position(VH v) const { return to_vec(mesh_->points()[v.idx()]); }
  void set_position(VH v, const std::array<double, 3>& p) {
    mesh_->points()[v.idx()] = HalfedgeMesh::Point(p[0], p[1], p[2]);
  }
  ComponentTable& components() { return components_; }
  const ComponentTable& components() const { return components_; }

  std::size_t live_vertices() const { return live_vertices_; }
  std::size_t live_faces() const { return live_faces_; }
  // Vertices and faces that left the surface (a collapse, a dumped component).
  void forget(std::size_t vertices, std::size_t faces) {
    live_vertices_ -= vertices;
    live_faces_ -= faces;
  }
  // Bits 2 * axis + side of the cube faces p lies on (VertexRecord::border).
  std::uint8_t border_bits(const std::array<double, 3>& p) const;

  // Room for nv vertices, ne edges and nf faces, grown by at least a quarter when it must grow (a
  // growing array doubles: up to half its room would stay spare).
  void make_room(std::size_t nv, std::size_t ne, std::size_t nf);

  // The one path new elements take: room for `new_vertices` more vertices (numbered from the
  // returned index on, their records and points for the caller to fill) and for `triangles` more
  // triangles (at most three new edges and one face each); `exact`: exactly that room (a merge: the
  // larger surface does not double its storage for it), else make_room()'s growth. Then
  // add_triangle() for each (invalid when it would make the surface non-manifold), then
  // end_append(), which makes the new edges' records fresh and counts the new vertices and faces.
  std::size_t begin_append(std::size_t new_vertices, std::size_t triangles, bool exact);
  FH add_triangle(VH a, VH b, VH c);
  void end_append();

  // Compacts the mesh (`give_back`: its room beyond the live elements too) and renumbers what
  // refers to vertices here: the layer ids, the isolated vertices and the components (which pick
  // their members again). The caller renumbers the rest (the collapser's queues).
  void compact(bool give_back);

  // Welding a layer to the one before it (surface_layers.cpp): the ids of the last layer's
  // vertices, this layer's so far, and the positions of the vertices this layer creates (numbered
  // after the mesh's, their storage made at once by begin_append()).
  IdMap& previous_ids() { return previous_ids_; }
  const IdMap& previous_ids() const { return previous_ids_; }
  IdMap& current_ids() { return current_ids_; }
  std::vector<std::array<double, 3>>& new_positions() { return new_positions_; }
  // Only the layer just added can be repeated by the next one.
  void end_layer() {
    previous_ids_.swap(current_ids_);
    current_ids_.clear();
  }
  // Vertices of the last layer that no triangle uses yet.
  std::vector<std::int32_t>& isolated() { return isolated_; }
  const std::vector<std::int32_t>& isolated() const { return isolated_; }
  // Drops those that are still unused (they would never be finished).
  void drop_isolated_vertices();

  // The live surface as a plain mesh.
  mesh::SurfaceMesh snapshot() const;

private:
  std::unique_ptr<HalfedgeMesh> mesh_; // made empty, with any room a surface destroyed here left
  ComponentTable components_;
  IdMap previous_ids_; // ids of the last layer: the next one may repeat them
  IdMap current_ids_;
  std::vector<std::int32_t> isolated_;
  std::vector<std::array<double, 3>> new_positions_;
  std::array<double, 3> cube_hi_{};
  std::size_t live_vertices_ = 0;
  std::size_t live_faces_ = 0;
  std::size_t append_vertices_ = 0, append_edges_ = 0, append_faces_ = 0; // where begin_append() began
};

} // namespace geotandem::tandem::detail
