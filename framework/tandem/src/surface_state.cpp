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
  s.options = options_;
  s.front = front_;
  s.last_rank = last_rank_;
  s.origin = costs_.origin();
  s.counters = counters_;

  // Components: the live roots, numbered in order (a find without path halving: this is const).
  auto root_of = [&](std::int32_t c) {
    while (components_.at(c).parent != c)
      c = components_.at(c).parent;
    return c;
  };
  std::vector<std::int32_t> component_index(components_.record_count(), -1);
  std::vector<std::int32_t> vertex_index(mesh_->n_vertices(), -1);
  s.points.reserve(live_vertices_);
  s.vertices.reserve(live_vertices_);
  for (std::size_t i = 0; i < mesh_->n_vertices(); ++i) {
    if (!vrec_[i].alive) continue;
    vertex_index[i] = static_cast<std::int32_t>(s.points.size());
    const detail::VertexRecord& r = vrec_[i];
    const std::int32_t root = root_of(r.component);
    std::int32_t& c = component_index[static_cast<std::size_t>(root)];
    if (c < 0) {
      c = static_cast<std::int32_t>(s.component_keys.size());
      s.component_keys.push_back(components_.at(root).key);
      s.component_samples.push_back(components_.at(root).samples);
    }
    s.points.push_back(detail::to_vec(points_[i]));
    s.vertices.push_back(detail::state_vertex(r, c));
  }
  auto vertex = [&](VH v) { return static_cast<std::uint32_t>(vertex_index[static_cast<std::size_t>(v.idx())]); };

  s.triangles.reserve(live_faces_);
  for (std::size_t i = 0; i < mesh_->n_faces(); ++i) {
    if (!frec_[i].alive) continue;
    const HH h = mesh_->halfedge_handle(FH(static_cast<int>(i)));
    s.triangles.push_back({vertex(mesh_->from_vertex_handle(h)), vertex(mesh_->to_vertex_handle(h)),
                           vertex(mesh_->to_vertex_handle(mesh_->next_halfedge_handle(h)))});
  }
  for (std::size_t i = 0; i < mesh_->n_edges(); ++i) {
    const detail::EdgeRecord& r = erec_[i];
    if (!r.alive || r.state == EdgeState::idle) continue;
    const HH h = mesh_->halfedge_handle(EH(static_cast<int>(i)), 0);
    std::uint32_t v0 = vertex(mesh_->from_vertex_handle(h)), v1 = vertex(mesh_->to_vertex_handle(h));
    if (v1 < v0) std::swap(v0, v1);
    s.edges.push_back(
        {v0, v1, r.state, r.key, r.state == EdgeState::candidate ? queues_.pending(r) : detail::Pending{}});
  }
  // Edges and ids in a canonical order (the mesh numbers edges in the order they were made): the
  // record of a surface rebuilt from a record is then the same record.
  std::sort(s.edges.begin(), s.edges.end(), [](const detail::StateEdge& x, const detail::StateEdge& y) {
    return x.v0 != y.v0 ? x.v0 < y.v0 : x.v1 < y.v1;
  });
  previous_ids_.for_each([&](std::uint64_t id, std::int32_t v) {
    if (v >= 0 && vertex_index[static_cast<std::size_t>(v)] >= 0)
      s.previous_ids.emplace_back(id, static_cast<std::uint32_t>(vertex_index[static_cast<std::size_t>(v)]));
  });
  std::sort(s.previous_ids.begin(), s.previous_ids.end());
  for (std::int32_t v : isolated_)
    if (vertex_index[static_cast<std::size_t>(v)] >= 0)
      s.isolated.push_back(static_cast<std::uint32_t>(vertex_index[static_cast<std::size_t>(v)]));
  return s;
}

void WorkingSurface::Engine::restore_edge(VH a, VH b, const detail::StateEdge& edge, std::size_t index) {
  const HH h = a != b ? detail::find_halfedge(*mesh_, a, b) : HH();
  if (!h.is_valid())
    throw DataError("working surface state: edge " + std::to_string(index) + " (" + std::to_string(a.idx()) + ", " +
                    std::to_string(b.idx()) + ") is not an edge of the surface");
  const EdgeState state = edge.state;
  if (state != EdgeState::idle && state != EdgeState::candidate && state != EdgeState::delayed &&
      state != EdgeState::parked)
    throw DataError("working surface state: edge " + std::to_string(index) + " has an unknown state");
  const EH e = mesh_->edge_handle(h);
  if (erec(e).state != EdgeState::idle) set_state(e, EdgeState::idle, 0.0);
  set_state(e, state, edge.key);
  if (state == EdgeState::candidate) pending(e) = edge.pending;
}

void WorkingSurface::Engine::import_state(detail::SurfaceState&& s) {
  const std::size_t nv = s.points.size(), nt = s.triangles.size();
  if (s.vertices.size() != nv)
    throw DataError("working surface state: " + std::to_string(nv) + " points but " +
                    std::to_string(s.vertices.size()) + " vertex records");
  front_ = s.front;
  last_rank_ = s.last_rank;
  costs_.set_origin(s.origin);
  counters_ = s.counters;

  // Components first: vertices refer to them by index, which is also their id in the table.
  components_ = detail::ComponentTable{};
  for (std::size_t c = 0; c < s.component_keys.size(); ++c)
    components_.create(s.component_keys[c], -1, c < s.component_samples.size() ? s.component_samples[c] : 0);

  // Room for at most three edges and one face per triangle; they are appended as the triangles go
  // in, so only the room they use is touched.
  mesh_->reserve(nv, 3 * nt, nt);
  mesh_->resize(nv, 0, 0);
  refresh();
  for (std::size_t i = 0; i < nv; ++i) {
    const detail::StateVertex& r = s.vertices[i];
    if (r.component < 0 || static_cast<std::size_t>(r.component) >= s.component_keys.size())
      throw DataError("working surface state: vertex " + std::to_string(i) + " belongs to component " +
                      std::to_string(r.component) + " of " + std::to_string(s.component_keys.size()));
    vrec_[i] = detail::vertex_record(r, r.component);
    const detail::Vec3& p = s.points[i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw DataError("working surface state: vertex " + std::to_string(i) + " has a non-finite position");
    points_[i] = detail::HalfedgeMesh::Point(p[0], p[1], p[2]);
    detail::ComponentRecord& c = components_.at(r.component);
    if (c.member < 0) c.member = static_cast<std::int32_t>(i);
  }
  live_vertices_ = nv;
  for (std::size_t c = 0; c < s.component_keys.size(); ++c)
    if (components_.at(static_cast<std::int32_t>(c)).member < 0)
      throw DataError("working surface state: component " + std::to_string(c) + " has no vertex");

  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = s.triangles[t];
    if (tri[0] >= nv || tri[1] >= nv || tri[2] >= nv || tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
      throw DataError("working surface state: triangle " + std::to_string(t) +
                      " repeats a vertex or refers to one beyond the " + std::to_string(nv));
    const FH f = detail::insert_triangle(*mesh_, VH(static_cast<int>(tri[0])), VH(static_cast<int>(tri[1])),
                                         VH(static_cast<int>(tri[2])));
    if (!f.is_valid())
      throw DataError("working surface state: triangle " + std::to_string(t) +
                      " would make the surface non-manifold or flip its orientation");
    if (vrec_[tri[0]].component != vrec_[tri[1]].component || vrec_[tri[1]].component != vrec_[tri[2]].component)
      throw DataError("working surface state: triangle " + std::to_string(t) + " joins different components");
  }
  refresh();
  live_faces_ = nt;
  for (std::size_t i = 0; i < mesh_->n_edges(); ++i) {
    erec_[i] = detail::EdgeRecord{};
    erec_[i].alive = true;
  }
  costs_.recompute_face_terms(frec_); // the vertices' sums over their triangles, which the state does not carry

  // Queues: every edge that is not idle goes back to its place with its key.
  for (std::size_t i = 0; i < s.edges.size(); ++i) {
    const detail::StateEdge& se = s.edges[i];
    if (se.v0 >= nv || se.v1 >= nv)
      throw DataError("working surface state: edge " + std::to_string(i) + " refers to a vertex beyond the " +
                      std::to_string(nv));
    restore_edge(VH(static_cast<int>(se.v0)), VH(static_cast<int>(se.v1)), se, i);
  }
  find_parked_faces(); // the state does not carry them: the next merge then places only the edges it may free

  previous_ids_.clear();
  current_ids_.clear();
  for (const auto& [id, v] : s.previous_ids) {
    if (v >= nv || id == detail::kNoLatticeId)
      throw DataError("working surface state: a lattice id of the last layer names vertex " + std::to_string(v) +
                      " of " + std::to_string(nv));
    previous_ids_.insert(id, static_cast<std::int32_t>(v));
  }
  isolated_.clear();
  for (std::uint32_t v : s.isolated) {
    if (v >= nv)
      throw DataError("working surface state: isolated vertex " + std::to_string(v) + " of " + std::to_string(nv));
    isolated_.push_back(static_cast<std::int32_t>(v));
  }
  // Any component may be finished already (its waiting edges just left W): let dump() look.
  for (std::size_t c = 0; c < s.component_keys.size(); ++c)
    components_.requeue(static_cast<std::int32_t>(c));
}

} // namespace geotandem::tandem
