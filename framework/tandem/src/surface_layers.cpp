// extract(k) and delay(k): appending a layer to the working surface.
#include <cmath>
#include <string>

#include "geotandem/core/error.hpp"
#include "surface_engine.hpp"
#include "triangle_insert.hpp"

namespace geotandem::tandem {

using detail::EdgeState;
using detail::Vec3;
using detail::operator+;
using detail::operator-;
using detail::operator*;

std::uint8_t WorkingSurface::Engine::border_bits(const std::array<double, 3>& p) const {
  std::uint8_t bits = 0;
  for (unsigned i = 0; i < 3; ++i) {
    if (p[i] == 0.0) bits |= static_cast<std::uint8_t>(1u << (2 * i));
    if (p[i] == cube_hi_[i]) bits |= static_cast<std::uint8_t>(2u << (2 * i));
  }
  return bits;
}

namespace {
std::string layer_where(std::int64_t rank) {
  return "layer " + std::to_string(rank);
}
} // namespace

WorkingSurface::Engine::VH WorkingSurface::Engine::weld_or_create(std::uint64_t id, const std::array<double, 3>& p,
                                                                  std::int64_t rank, std::size_t index) {
  if (id == detail::kNoLatticeId)
    throw DataError(layer_where(rank) + ": vertex " + std::to_string(index) + " has the reserved id 2^64-1");
  std::int32_t v = previous_ids_.find(id);
  if (v >= 0) {
    const detail::VertexRecord& r = vrec_[v];
    if (!r.alive || r.lattice_id != id)
      throw DataError(layer_where(rank) + ": vertex " + std::to_string(index) + " repeats lattice edge " +
                          std::to_string(id) + " of the previous layer, which was simplified away",
                      {}, "add each layer before the front passes it (activate(k) only after add_layer(k))");
    return VH(v);
  }
  v = current_ids_.find(id);
  if (v >= 0) return VH(v); // listed twice in one layer: the same vertex
  for (double x : p)
    if (!std::isfinite(x))
      throw DataError(layer_where(rank) + ": vertex " + std::to_string(index) + " has a non-finite position");
  // A new vertex: its index is reserved now, the storage grows once for the whole layer.
  const auto vh = static_cast<std::int32_t>(mesh_->n_vertices() + new_positions_.size());
  new_positions_.push_back(p);
  current_ids_.insert(id, vh);
  return VH(vh);
}

void WorkingSurface::Engine::drop_isolated_vertices() {
  for (std::int32_t i : isolated_) {
    const VH v(i);
    detail::VertexRecord& r = vrec(v);
    if (!r.alive || !mesh_->is_isolated(v)) continue;
    components_.remove(components_.find(r.component));
    r.alive = false;
    --live_vertices_;
  }
  isolated_.clear();
}

namespace {

// A vertex's share of its component's samples (Layer::vertex_samples), counted by one block only:
// a sample plane between two blocks is extracted by both, and their vertices there are welded at
// the merge. A sample coordinate x belongs to the block with lo <= x < hi, or x == hi on the
// cube's far face. Weighted vertices lie on edges along the sample axis (x = the edge's start)
// or on samples, so their positions' integer parts are their samples.
std::int64_t counted_samples(const Layer& layer, std::size_t i, const Region& region) {
  if (layer.vertex_samples.size() != layer.vertex_ids.size() || layer.vertex_samples[i] == 0) return 0;
  const auto& p = layer.positions[i];
  const std::int64_t x[3] = {static_cast<std::int64_t>(p[0]), static_cast<std::int64_t>(p[1]),
                             static_cast<std::int64_t>(p[2])};
  const volume::Box& cube = region.cube();
  for (const volume::Box& b : region.blocks()) {
    bool mine = true;
    for (int a = 0; a < 3 && mine; ++a)
      mine = b.lo[a] <= x[a] && (x[a] < b.hi[a] || (x[a] == b.hi[a] && b.hi[a] == cube.hi[a]));
    if (mine) return layer.vertex_samples[i];
  }
  return 0;
}

} // namespace

void WorkingSurface::Engine::add_layer(const Layer& layer) {
  if (layer.axis != axis_)
    throw InvalidArgument(layer_where(layer.rank) + " is along axis " + std::to_string(layer.axis) +
                          " but the surface is extracted along axis " + std::to_string(axis_));
  if (layer.rank <= last_rank_)
    throw InvalidArgument(layer_where(layer.rank) + " comes after layer " + std::to_string(last_rank_), {},
                          "layers must come in increasing rank");
  if (static_cast<double>(layer.rank) <= front_)
    throw InvalidArgument(layer_where(layer.rank) + " is not ahead of the front at " + std::to_string(front_));
  if (layer.positions.size() != layer.vertex_ids.size())
    throw DataError(layer_where(layer.rank) + ": " + std::to_string(layer.vertex_ids.size()) + " ids but " +
                    std::to_string(layer.positions.size()) + " positions");
  last_rank_ = layer.rank;

  // Vertices: weld to the previous layer by lattice-edge id, or create.
  const std::size_t n = layer.vertex_ids.size();
  const std::size_t first_new = mesh_->n_vertices();
  std::vector<VH> handles(n);
  new_positions_.clear();
  for (std::size_t i = 0; i < n; ++i)
    handles[i] = weld_or_create(layer.vertex_ids[i], layer.positions[i], layer.rank, i);
  const std::size_t edges_before = mesh_->n_edges(), faces_before = mesh_->n_faces();
  const std::size_t nt = layer.triangles.size();
  // Room for every new vertex, and for at most three new edges and one face per triangle; edges
  // and faces are appended as the triangles go in, so only the room they use is touched.
  make_room(first_new + new_positions_.size(), edges_before + 3 * nt, faces_before + nt);
  mesh_->resize(first_new + new_positions_.size(), edges_before, faces_before);
  refresh();
  for (std::size_t k = 0; k < new_positions_.size(); ++k)
    points_[first_new + k] =
        detail::HalfedgeMesh::Point(new_positions_[k][0], new_positions_[k][1], new_positions_[k][2]);
  for (std::size_t i = 0; i < n; ++i) {
    const VH v = handles[i];
    detail::VertexRecord& r = vrec(v);
    if (static_cast<std::size_t>(v.idx()) < first_new || r.alive) continue;
    const Vec3 p = position(v);
    r = detail::VertexRecord{};
    r.height = p[static_cast<std::size_t>(axis_)];
    r.rad = 1.0;
    r.border = border_bits(p);
    r.lattice_id = layer.vertex_ids[i];
    r.component = components_.create(r.lattice_id, v.idx(), counted_samples(layer, i, region_));
    r.alive = true;
    ++live_vertices_;
  }

  // Triangles: insert, accumulate shape quadrics, join components.
  std::vector<FH> faces;
  faces.reserve(layer.triangles.size());
  for (std::size_t t = 0; t < layer.triangles.size(); ++t) {
    const auto& tri = layer.triangles[t];
    if (tri[0] >= n || tri[1] >= n || tri[2] >= n)
      throw DataError(layer_where(layer.rank) + ": triangle " + std::to_string(t) + " refers to a vertex beyond the " +
                      std::to_string(n) + " of the layer");
    const VH v0 = handles[tri[0]], v1 = handles[tri[1]], v2 = handles[tri[2]];
    if (v0 == v1 || v1 == v2 || v0 == v2)
      throw DataError(layer_where(layer.rank) + ": triangle " + std::to_string(t) + " repeats a vertex");
    const FH f = detail::insert_triangle(*mesh_, v0, v1, v2);
    if (!f.is_valid())
      throw DataError(layer_where(layer.rank) + ": triangle " + std::to_string(t) + " (lattice edges " +
                          std::to_string(layer.vertex_ids[tri[0]]) + ", " + std::to_string(layer.vertex_ids[tri[1]]) +
                          ", " + std::to_string(layer.vertex_ids[tri[2]]) +
                          ") would make the surface non-manifold or flip its orientation",
                      {}, "the layer source must produce a consistently oriented 2-manifold");
    faces.push_back(f);
    const Vec3 p0 = position(v0), p1 = position(v1), p2 = position(v2);
    const Vec3 normal = detail::cross(p1 - p0, p2 - p0);
    const double twice_area = detail::norm(normal);
    if (twice_area > 0.0) {
      const Vec3 unit = (1.0 / twice_area) * normal;
      const double d = -detail::dot(unit, p0);
      const double area = 0.5 * twice_area;
      for (VH v : {v0, v1, v2})
        vrec(v).shape.add_plane(unit, d, area);
    }
    components_.unite(components_.unite(vrec(v0).component, vrec(v1).component), vrec(v2).component);
  }
  refresh();
  live_faces_ += faces.size();
  // Vertices no triangle uses (a source listing more than it needs) would never be finished: drop
  // those of the previous layer that this one did not use either; keep this layer's for the next.
  drop_isolated_vertices();
  for (std::size_t i = first_new; i < mesh_->n_vertices(); ++i)
    if (mesh_->is_isolated(VH(static_cast<int>(i)))) isolated_.push_back(static_cast<std::int32_t>(i));
  counters_.input_triangles += faces.size();

  // Face terms, then delay(k): every edge of the new triangles waits in W.
  for (FH f : faces)
    costs_.add_face_terms(f);
  for (FH f : faces) {
    HH h = mesh_->halfedge_handle(f);
    for (int k = 0; k < 3; ++k, h = mesh_->next_halfedge_handle(h)) {
      const EH e = mesh_->edge_handle(h);
      detail::EdgeRecord& r = erec(e);
      if (!r.alive) {
        r = detail::EdgeRecord{};
        r.alive = true;
      }
      if (r.state == EdgeState::delayed) continue; // both of its triangles are new: already done
      set_state(e, EdgeState::delayed, front_rule_->key(geometry_of(mesh_->halfedge_handle(e, 0))));
    }
  }

  // Only this layer's vertices can be repeated by the next one.
  previous_ids_.swap(current_ids_);
  current_ids_.clear();
}

} // namespace geotandem::tandem
