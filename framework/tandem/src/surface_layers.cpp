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

namespace {
std::string layer_where(std::int64_t rank) {
  return "layer " + std::to_string(rank);
}
} // namespace

WorkingSurface::Engine::VH WorkingSurface::Engine::weld_or_create(std::uint64_t id, const std::array<double, 3>& p,
                                                                  std::int64_t rank, std::size_t index) {
  if (id == detail::kNoLatticeId)
    throw DataError(layer_where(rank) + ": vertex " + std::to_string(index) + " has the reserved id 2^64-1");
  std::int32_t v = storage_.previous_ids().find(id);
  if (v >= 0) {
    const detail::VertexRecord& r = storage_.vertex(VH(v));
    if (!r.alive || r.lattice_id != id)
      throw DataError(layer_where(rank) + ": vertex " + std::to_string(index) + " repeats lattice edge " +
                          std::to_string(id) + " of the previous layer, which was simplified away",
                      {}, "add each layer before the front passes it (activate(k) only after add_layer(k))");
    return VH(v);
  }
  v = storage_.current_ids().find(id);
  if (v >= 0) return VH(v); // listed twice in one layer: the same vertex
  for (double x : p)
    if (!std::isfinite(x))
      throw DataError(layer_where(rank) + ": vertex " + std::to_string(index) + " has a non-finite position");
  // A new vertex: its index is reserved now, the storage grows once for the whole layer.
  std::vector<std::array<double, 3>>& created = storage_.new_positions();
  const auto vh = static_cast<std::int32_t>(storage_.mesh().n_vertices() + created.size());
  created.push_back(p);
  storage_.current_ids().insert(id, vh);
  return VH(vh);
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
  if (static_cast<double>(layer.rank) <= collapser_.front())
    throw InvalidArgument(layer_where(layer.rank) + " is not ahead of the front at " +
                          std::to_string(collapser_.front()));
  if (layer.positions.size() != layer.vertex_ids.size())
    throw DataError(layer_where(layer.rank) + ": " + std::to_string(layer.vertex_ids.size()) + " ids but " +
                    std::to_string(layer.positions.size()) + " positions");
  last_rank_ = layer.rank;

  // Vertices: weld to the previous layer by lattice-edge id, or create.
  const std::size_t n = layer.vertex_ids.size();
  std::vector<std::array<double, 3>>& created = storage_.new_positions();
  created.clear();
  std::vector<VH> handles(n);
  for (std::size_t i = 0; i < n; ++i)
    handles[i] = weld_or_create(layer.vertex_ids[i], layer.positions[i], layer.rank, i);
  const std::size_t nt = layer.triangles.size();
  const std::size_t first_new = storage_.begin_append(created.size(), nt, false);
  for (std::size_t k = 0; k < created.size(); ++k)
    storage_.set_position(VH(static_cast<int>(first_new + k)), created[k]);
  detail::ComponentTable& components = storage_.components();
  for (std::size_t i = 0; i < n; ++i) {
    const VH v = handles[i];
    detail::VertexRecord& r = storage_.vertex(v);
    if (static_cast<std::size_t>(v.idx()) < first_new || r.alive) continue;
    const Vec3 p = storage_.position(v);
    r = detail::VertexRecord{};
    r.height = p[static_cast<std::size_t>(axis_)];
    r.rad = 1.0;
    r.border = storage_.border_bits(p);
    r.lattice_id = layer.vertex_ids[i];
    r.component = components.create(r.lattice_id, v.idx(), counted_samples(layer, i, region_));
    r.alive = true;
  }

  // Triangles: insert, accumulate shape quadrics, join components.
  std::vector<FH> faces;
  faces.reserve(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = layer.triangles[t];
    if (tri[0] >= n || tri[1] >= n || tri[2] >= n)
      throw DataError(layer_where(layer.rank) + ": triangle " + std::to_string(t) + " refers to a vertex beyond the " +
                      std::to_string(n) + " of the layer");
    const VH v0 = handles[tri[0]], v1 = handles[tri[1]], v2 = handles[tri[2]];
    if (v0 == v1 || v1 == v2 || v0 == v2)
      throw DataError(layer_where(layer.rank) + ": triangle " + std::to_string(t) + " repeats a vertex");
    const FH f = storage_.add_triangle(v0, v1, v2);
    if (!f.is_valid())
      throw DataError(layer_where(layer.rank) + ": triangle " + std::to_string(t) + " (lattice edges " +
                          std::to_string(layer.vertex_ids[tri[0]]) + ", " + std::to_string(layer.vertex_ids[tri[1]]) +
                          ", " + std::to_string(layer.vertex_ids[tri[2]]) +
                          ") would make the surface non-manifold or flip its orientation",
                      {}, "the layer source must produce a consistently oriented 2-manifold");
    faces.push_back(f);
    const Vec3 p0 = storage_.position(v0), p1 = storage_.position(v1), p2 = storage_.position(v2);
    const Vec3 normal = detail::cross(p1 - p0, p2 - p0);
    const double twice_area = detail::norm(normal);
    if (twice_area > 0.0) {
      const Vec3 unit = (1.0 / twice_area) * normal;
      const double d = -detail::dot(unit, p0);
      const double area = 0.5 * twice_area;
      for (VH v : {v0, v1, v2})
        storage_.vertex(v).shape.add_plane(unit, d, area);
    }
    components.unite(components.unite(storage_.vertex(v0).component, storage_.vertex(v1).component),
                     storage_.vertex(v2).component);
  }
  storage_.end_append();
  collapser_.grown();
  // Vertices no triangle uses (a source listing more than it needs) would never be finished: drop
  // those of the previous layer that this one did not use either; keep this layer's for the next.
  storage_.drop_isolated_vertices();
  for (std::size_t i = first_new; i < storage_.mesh().n_vertices(); ++i)
    if (storage_.mesh().is_isolated(VH(static_cast<int>(i))))
      storage_.isolated().push_back(static_cast<std::int32_t>(i));
  collapser_.counters().input_triangles += faces.size();

  // Face terms, then delay(k): every edge of the new triangles waits in W.
  collapser_.delay_new_faces(faces);

  storage_.end_layer();
}

} // namespace geotandem::tandem
