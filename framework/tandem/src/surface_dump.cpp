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
  detail::ComponentTable& components = storage_.components();
  for (std::int32_t c : components.take_maybe_finished()) {
    const std::int32_t root = components.find(c);
    const detail::ComponentRecord& r = components.at(root);
    if (!r.alive || r.waiting != 0) continue;
    dump_component(root);
    ++dumped;
  }
  maybe_collect_garbage();
  return dumped;
}

void WorkingSurface::Engine::dump_component(std::int32_t root) {
  const detail::ComponentRecord record = storage_.components().at(root);
  assert(record.member >= 0 && storage_.vertex(VH(record.member)).alive);
  mesh::Component component;
  component.key = record.key;
  std::vector<VH> order;
  std::vector<FH> faces;
  detail::HalfedgeMesh& mesh = storage_.mesh();
  component.surface = reader_.read(mesh, mesh.points(), VH(record.member), collapser_.marks(), order, faces);

  if (sink_) {
    component.stats = mesh::measure_component(component.surface, cube_);
    component.stats.samples = record.samples;
    sink_->commit(component);
  }

  // Remove it: nothing outside the component refers to its elements.
  for (VH v : order) {
    const HH first = mesh.halfedge_handle(v);
    HH h = first;
    do {
      const EH e = mesh.edge_handle(h);
      detail::EdgeRecord& er = storage_.edge(e);
      if (er.alive) {
        if (er.state != EdgeState::idle) collapser_.set_state(e, EdgeState::idle, 0.0);
        er.alive = false;
      }
      h = detail::next_outgoing(mesh, h);
    } while (h != first);
    storage_.vertex(v).alive = false;
  }
  for (FH f : faces)
    storage_.face(f).alive = false;
  storage_.components().remove(root);
  storage_.forget(order.size(), faces.size());
  ++collapser_.counters().components_dumped;
  collapser_.counters().triangles_dumped += faces.size();
}

void WorkingSurface::Engine::maybe_collect_garbage() {
  // Compaction costs a pass over everything held; do it when half the storage is dead (amortised
  // O(1) per removed element) and there is enough of it to matter. (At two thirds, as before, the
  // storage held was up to three times the live surface.) The room stays: the next layers fill it
  // again, in pages already faulted in (giving it back made the kernel zero and map them anew
  // after every compaction).
  const std::size_t live_faces = storage_.live_faces();
  const std::size_t dead_faces = storage_.mesh().n_faces() - live_faces;
  if (dead_faces > collapser_.options().compaction_min_dead && dead_faces > live_faces) collect_garbage(false);
}

void WorkingSurface::Engine::compact() {
  // A compacted mesh has exactly the room it needs; only compact when that gives back enough.
  const std::size_t room = storage_.mesh().vertex_capacity(), live_vertices = storage_.live_vertices(),
                    live_faces = storage_.live_faces();
  if (storage_.mesh().n_faces() - live_faces > live_faces / 8 || room > live_vertices + live_vertices / 8)
    collect_garbage(true);
}

void WorkingSurface::Engine::collect_garbage(bool give_back) {
  collapser_.forget_numbers();
  storage_.compact(give_back); // renumbers the layer ids, the isolated vertices and the components
  reader_.release();
  collapser_.renumbered(give_back); // the queues from the records that moved with their edges
}

} // namespace geotandem::tandem
