// dumping(): finished components leave the working surface; compaction of the mesh afterwards.
#include <algorithm>
#include <cassert>
#include <string>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/measure.hpp"
#include "surface_engine.hpp"

namespace geotandem::tandem {

using detail::EdgeState;

std::size_t WorkingSurface::Engine::dump() {
  std::size_t dumped = 0;
  for (std::int32_t c : components_.take_maybe_finished()) {
    const std::int32_t root = components_.find(c);
    const detail::ComponentRecord& r = components_.at(root);
    if (!r.alive || r.waiting != 0) continue;
    dump_component(root);
    ++dumped;
  }
  maybe_collect_garbage();
  return dumped;
}

void WorkingSurface::Engine::dump_component(std::int32_t root) {
  const detail::ComponentRecord record = components_.at(root);
  assert(record.member >= 0 && vrec(VH(record.member)).alive);
  mesh::Component component;
  component.key = record.key;
  std::vector<VH> order;
  std::vector<FH> faces;
  component.surface = reader_.read(*mesh_, points_, VH(record.member), marks_, order, faces);

  if (sink_) {
    component.stats = mesh::measure_component(component.surface, cube_);
    component.stats.samples = record.samples;
    sink_->commit(component);
  }

  // Remove it: nothing outside the component refers to its elements.
  for (VH v : order) {
    const HH first = mesh_->halfedge_handle(v);
    HH h = first;
    do {
      const EH e = mesh_->edge_handle(h);
      detail::EdgeRecord& er = erec(e);
      if (er.alive) {
        if (er.state != EdgeState::idle) set_state(e, EdgeState::idle, 0.0);
        er.alive = false;
      }
      h = detail::next_outgoing(*mesh_, h);
    } while (h != first);
    detail::VertexRecord& vr = vrec(v);
    vr.alive = false;
  }
  for (FH f : faces)
    frec(f).alive = false;
  components_.remove(root);
  live_vertices_ -= order.size();
  live_faces_ -= faces.size();
  ++counters_.components_dumped;
  counters_.triangles_dumped += faces.size();
}

void WorkingSurface::Engine::maybe_collect_garbage() {
  // Compaction costs a pass over everything held; do it when half the storage is dead (amortised
  // O(1) per removed element) and there is enough of it to matter. (At two thirds, as before, the
  // storage held was up to three times the live surface.) The room stays: the next layers fill it
  // again, in pages already faulted in (giving it back made the kernel zero and map them anew
  // after every compaction).
  const std::size_t dead_faces = mesh_->n_faces() - live_faces_;
  if (dead_faces > options_.compaction_min_dead && dead_faces > live_faces_) collect_garbage(false);
}

void WorkingSurface::Engine::compact() {
  // A compacted mesh has exactly the room it needs; only compact when that gives back enough.
  const std::size_t room = mesh_->vertex_capacity();
  if (mesh_->n_faces() - live_faces_ > live_faces_ / 8 || room > live_vertices_ + live_vertices_ / 8)
    collect_garbage(true);
}

void WorkingSurface::Engine::make_room(std::size_t nv, std::size_t ne, std::size_t nf) {
  const std::size_t v = mesh_->vertex_capacity(), e = mesh_->edge_capacity(), f = mesh_->face_capacity();
  const auto room = [](std::size_t need, std::size_t have) {
    return need <= have ? have : std::max(need, have + have / 4);
  };
  if (nv > v || ne > e || nf > f) mesh_->reserve(room(nv, v), room(ne, e), room(nf, f));
}

void WorkingSurface::Engine::collect_garbage(bool give_back) {
  queues_.forget_numbers();
  const std::vector<std::int32_t> moved = mesh_->compact(give_back);
  reader_.release();
  marks_.clear();
  refresh();
  costs_.recompute_face_terms(frec_);

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
  for (std::size_t i = 0; i < mesh_->n_vertices(); ++i) {
    detail::VertexRecord& r = vrec_[i];
    r.component = renumber[static_cast<std::size_t>(r.component)];
    detail::ComponentRecord& c = components_.at(r.component);
    if (c.member < 0) c.member = static_cast<std::int32_t>(i);
  }

  // Queues: rebuilt from the edges' states (the records moved with the edges).
  queues_.rebuild(erec_, mesh_->n_edges(), give_back);
  ++counters_.garbage_collections;
}

mesh::SurfaceMesh WorkingSurface::Engine::snapshot() const {
  mesh::SurfaceMesh out;
  std::vector<std::int32_t> index(mesh_->n_vertices(), -1);
  for (std::size_t i = 0; i < mesh_->n_vertices(); ++i) {
    if (!vrec_[i].alive) continue;
    index[i] = static_cast<std::int32_t>(out.points.size());
    out.points.push_back(detail::to_vec(points_[i]));
  }
  for (std::size_t i = 0; i < mesh_->n_faces(); ++i) {
    if (!frec_[i].alive) continue;
    const HH h = mesh_->halfedge_handle(FH(static_cast<int>(i)));
    const VH v0 = mesh_->from_vertex_handle(h), v1 = mesh_->to_vertex_handle(h),
             v2 = mesh_->to_vertex_handle(mesh_->next_halfedge_handle(h));
    out.triangles.push_back({static_cast<std::uint32_t>(index[static_cast<std::size_t>(v0.idx())]),
                             static_cast<std::uint32_t>(index[static_cast<std::size_t>(v1.idx())]),
                             static_cast<std::uint32_t>(index[static_cast<std::size_t>(v2.idx())])});
  }
  return out;
}

} // namespace geotandem::tandem
