// The working surface as plain data and back (surface_state.hpp): what the wire format encodes and
// what a merge welds.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "geotandem/core/error.hpp"
#include "surface_engine.hpp"
#include "triangle_insert.hpp"

namespace geotandem::tandem {

using detail::EdgeState;

detail::SurfaceState WorkingSurface::Engine::export_state() const {
  detail::SurfaceState s;
  s.cube = cube_;
  s.region = region_;
  s.axis = axis_;
  s.options = collapser_.options();
  s.front = collapser_.front();
  s.last_rank = last_rank_;
  s.origin = collapser_.costs().origin();
  s.counters = collapser_.counters();
  const detail::HalfedgeMesh& mesh = storage_.mesh();
  const detail::ComponentTable& components = storage_.components();

  // Components: the live roots, numbered in order (a find without path halving: this is const).
  auto root_of = [&](std::int32_t c) {
    while (components.at(c).parent != c)
      c = components.at(c).parent;
    return c;
  };
  std::vector<std::int32_t> component_index(components.record_count(), -1);
  std::vector<std::int32_t> vertex_index(mesh.n_vertices(), -1);
  s.points.reserve(storage_.live_vertices());
  s.vertices.reserve(storage_.live_vertices());
  for (std::size_t i = 0; i < mesh.n_vertices(); ++i) {
    const detail::VertexRecord& r = mesh.vertex_records()[i];
    if (!r.alive) continue;
    vertex_index[i] = static_cast<std::int32_t>(s.points.size());
    const std::int32_t root = root_of(r.component);
    std::int32_t& c = component_index[static_cast<std::size_t>(root)];
    if (c < 0) {
      c = static_cast<std::int32_t>(s.component_keys.size());
      s.component_keys.push_back(components.at(root).key);
      s.component_samples.push_back(components.at(root).samples);
    }
    s.points.push_back(detail::to_vec(mesh.points()[i]));
    s.vertices.push_back(detail::state_vertex(r, c));
  }
  auto vertex = [&](VH v) { return static_cast<std::uint32_t>(vertex_index[static_cast<std::size_t>(v.idx())]); };

  s.triangles.reserve(storage_.live_faces());
  for (std::size_t i = 0; i < mesh.n_faces(); ++i) {
    if (!mesh.face_records()[i].alive) continue;
    const HH h = mesh.halfedge_handle(FH(static_cast<int>(i)));
    s.triangles.push_back({vertex(mesh.from_vertex_handle(h)), vertex(mesh.to_vertex_handle(h)),
                           vertex(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)))});
  }
  for (std::size_t i = 0; i < mesh.n_edges(); ++i) {
    const detail::EdgeRecord& r = mesh.edge_records()[i];
    if (!r.alive || r.state == EdgeState::idle) continue;
    const HH h = mesh.halfedge_handle(EH(static_cast<int>(i)), 0);
    std::uint32_t v0 = vertex(mesh.from_vertex_handle(h)), v1 = vertex(mesh.to_vertex_handle(h));
    if (v1 < v0) std::swap(v0, v1);
    s.edges.push_back(
        {v0, v1, r.state, r.key, r.state == EdgeState::candidate ? collapser_.queues().pending(r) : detail::Pending{}});
  }
  // Edges and ids in a canonical order (the mesh numbers edges in the order they were made): the
  // record of a surface rebuilt from a record is then the same record.
  std::sort(s.edges.begin(), s.edges.end(), [](const detail::StateEdge& x, const detail::StateEdge& y) {
    return x.v0 != y.v0 ? x.v0 < y.v0 : x.v1 < y.v1;
  });
  storage_.previous_ids().for_each([&](std::uint64_t id, std::int32_t v) {
    if (v >= 0 && vertex_index[static_cast<std::size_t>(v)] >= 0)
      s.previous_ids.emplace_back(id, static_cast<std::uint32_t>(vertex_index[static_cast<std::size_t>(v)]));
  });
  std::sort(s.previous_ids.begin(), s.previous_ids.end());
  for (std::int32_t v : storage_.isolated())
    if (vertex_index[static_cast<std::size_t>(v)] >= 0)
      s.isolated.push_back(static_cast<std::uint32_t>(vertex_index[static_cast<std::size_t>(v)]));
  return s;
}

void WorkingSurface::Engine::import_state(detail::SurfaceState&& s) {
  const std::size_t nv = s.points.size(), nt = s.triangles.size();
  if (s.vertices.size() != nv)
    throw DataError("working surface state: " + std::to_string(nv) + " points but " +
                    std::to_string(s.vertices.size()) + " vertex records");
  collapser_.set_front(s.front);
  last_rank_ = s.last_rank;
  collapser_.costs().set_origin(s.origin);
  collapser_.counters() = s.counters;

  // Components first: vertices refer to them by index, which is also their id in the table.
  detail::ComponentTable& components = storage_.components();
  components = detail::ComponentTable{};
  for (std::size_t c = 0; c < s.component_keys.size(); ++c)
    components.create(s.component_keys[c], -1, c < s.component_samples.size() ? s.component_samples[c] : 0);

  // The engine is fresh: its mesh is empty.
  storage_.begin_append(nv, nt, true);
  for (std::size_t i = 0; i < nv; ++i) {
    const detail::StateVertex& r = s.vertices[i];
    if (r.component < 0 || static_cast<std::size_t>(r.component) >= s.component_keys.size())
      throw DataError("working surface state: vertex " + std::to_string(i) + " belongs to component " +
                      std::to_string(r.component) + " of " + std::to_string(s.component_keys.size()));
    storage_.vertex(VH(static_cast<int>(i))) = detail::vertex_record(r, r.component);
    const detail::Vec3& p = s.points[i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw DataError("working surface state: vertex " + std::to_string(i) + " has a non-finite position");
    storage_.set_position(VH(static_cast<int>(i)), p);
    detail::ComponentRecord& c = components.at(r.component);
    if (c.member < 0) c.member = static_cast<std::int32_t>(i);
  }
  for (std::size_t c = 0; c < s.component_keys.size(); ++c)
    if (components.at(static_cast<std::int32_t>(c)).member < 0)
      throw DataError("working surface state: component " + std::to_string(c) + " has no vertex");

  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = s.triangles[t];
    if (tri[0] >= nv || tri[1] >= nv || tri[2] >= nv || tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
      throw DataError("working surface state: triangle " + std::to_string(t) +
                      " repeats a vertex or refers to one beyond the " + std::to_string(nv));
    const FH f =
        storage_.add_triangle(VH(static_cast<int>(tri[0])), VH(static_cast<int>(tri[1])), VH(static_cast<int>(tri[2])));
    if (!f.is_valid())
      throw DataError("working surface state: triangle " + std::to_string(t) +
                      " would make the surface non-manifold or flip its orientation");
    const auto component = [&](std::uint32_t v) { return storage_.vertex(VH(static_cast<int>(v))).component; };
    if (component(tri[0]) != component(tri[1]) || component(tri[1]) != component(tri[2]))
      throw DataError("working surface state: triangle " + std::to_string(t) + " joins different components");
  }
  storage_.end_append();
  collapser_.grown();
  collapser_.costs().recompute_face_terms(); // the vertices' sums over their triangles, which the state does not carry

  // Queues: every edge that is not idle goes back to its place with its key.
  for (std::size_t i = 0; i < s.edges.size(); ++i) {
    const detail::StateEdge& se = s.edges[i];
    if (se.v0 >= nv || se.v1 >= nv)
      throw DataError("working surface state: edge " + std::to_string(i) + " refers to a vertex beyond the " +
                      std::to_string(nv));
    collapser_.restore_edge(VH(static_cast<int>(se.v0)), VH(static_cast<int>(se.v1)), se, i);
  }
  collapser_
      .find_parked_faces(); // the state does not carry them: the next merge then places only the edges it may free

  storage_.previous_ids().clear();
  storage_.current_ids().clear();
  for (const auto& [id, v] : s.previous_ids) {
    if (v >= nv || id == detail::kNoLatticeId)
      throw DataError("working surface state: a lattice id of the last layer names vertex " + std::to_string(v) +
                      " of " + std::to_string(nv));
    storage_.previous_ids().insert(id, static_cast<std::int32_t>(v));
  }
  storage_.isolated().clear();
  for (std::uint32_t v : s.isolated) {
    if (v >= nv)
      throw DataError("working surface state: isolated vertex " + std::to_string(v) + " of " + std::to_string(nv));
    storage_.isolated().push_back(static_cast<std::int32_t>(v));
  }
  // Any component may be finished already (its waiting edges just left W): let dump() look.
  for (std::size_t c = 0; c < s.component_keys.size(); ++c)
    components.requeue(static_cast<std::int32_t>(c));
}

} // namespace geotandem::tandem
