#pragma once
// The machinery behind WorkingSurface: the working mesh and its records, the queues Q (candidates
// by cost) and W (edges delayed by the front, by reach; edges parked by the open faces), the
// component table, and the id maps that weld a layer to the previous one. The cost of a collapse
// (the face terms' sums and the evaluation) is its own object, EdgeCost (edge_cost.hpp): the engine
// tells it which triangles join or leave the surface.
//
// Edge life cycle (place()): an edge whose lag key is not below the front is delayed; else, if
// the open faces forbid it, parked; else its candidate is computed and it enters Q, or stays idle
// when the shape error exceeds E0. Any change of a or b re-places the edge. A popped candidate is
// collapsed unless the link condition or the flip test refuses it (then it stays idle until its
// neighbourhood changes; a flip gets one retry at the best of a, b and the midpoint).

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "attali_cost.hpp"
#include "collapse_distance.hpp"
#include "collapse_ops.hpp"
#include "component_reader.hpp"
#include "component_table.hpp"
#include "constraints.hpp"
#include "edge_cost.hpp"
#include "edge_queues.hpp"
#include "geotandem/tandem/simplify.hpp"
#include "id_map.hpp"
#include "surface_state.hpp"
#include "working_mesh.hpp"

namespace geotandem::tandem {

class WorkingSurface::Engine {
public:
  Engine(const volume::Geometry& cube, Region region, int axis, const SimplifyOptions& options,
         mesh::ComponentSink* sink, CollapseObserver* observer);
  // With keep_surface_storage() on, leaves its mesh's room to the next surface made on this thread.
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  void add_layer(const Layer& layer);
  void activate(double front);
  void simplify(const CancelToken* cancel);
  std::size_t dump();
  void set_region(Region region);
  void compact();
  // Storage for nv vertices, ne edges and nf faces, grown by at least a quarter when it must grow
  // (a growing array doubles: up to half its room would stay spare).
  void make_room(std::size_t nv, std::size_t ne, std::size_t nf);

  const Region& region() const { return region_; }
  double front() const { return front_; }
  std::size_t triangle_count() const { return live_faces_; }
  std::size_t vertex_count() const { return live_vertices_; }
  std::size_t component_count() const { return components_.alive_count(); }
  std::size_t waiting_edge_count() const { return queues_.waiting_count(); }
  const SimplifyCounters& counters() const { return counters_; }
  mesh::SurfaceMesh snapshot() const;

  // The surface as plain data, live elements only, densely numbered (surface_state.cpp).
  detail::SurfaceState export_state() const;
  // Fills a freshly constructed engine (same cube, region, axis and options as the state) with
  // `state`: the mesh, the records, the queues and the components. Throws DataError when the state
  // is inconsistent (an index out of range, a triangle that would make the surface non-manifold,
  // an edge that is not in the mesh).
  void import_state(detail::SurfaceState&& state);
  // Takes in the surface of a disjoint region of the same cube (both past their sweep), as plain
  // data (exported from its engine, or decoded from its wire form), welded by lattice ids; the
  // region becomes the union, but the parked edges are not placed again yet (surface_merge.cpp).
  // Throws InvalidArgument when the surfaces do not fit together and DataError when the weld does
  // not (two vertices with the same lattice id differ in position, a welded vertex is not on this
  // side's boundary, a seam edge is used in one direction twice): nothing is changed then; a
  // DataError from a triangle that still cannot go in leaves the engine in an unspecified state. The
  // state's parts are given back as soon as they are in: the larger surface grows while they go.
  void absorb_state(detail::SurfaceState&& other);
  // absorb_state(), then the edges parked by faces now inside the grown region placed again, the
  // simplification and the dumping: a whole merge. Returns the components dumped.
  std::size_t merge_state(detail::SurfaceState&& other, const CancelToken* cancel);
  // The union of both regions; throws InvalidArgument as absorb_state() does when the two do not
  // fit.
  Region merge_region(const Engine& other) const;
  Region merge_region_state(const detail::SurfaceState& other) const;
  Region merge_region_of(const Region& region, int axis, const SimplifyOptions& options, double front) const;
  mesh::ComponentSink* sink_of() const { return sink_; }
  CollapseObserver* observer_of() const { return observer_; }
  void set_outputs(mesh::ComponentSink* sink, CollapseObserver* observer) {
    sink_ = sink;
    observer_ = observer;
  }

private:
  using VH = detail::VH;
  using HH = detail::HH;
  using EH = detail::EH;
  using FH = detail::FH;

  // Raw views of the records; valid until the mesh grows or is compacted.
  void refresh();
  detail::VertexRecord& vrec(VH v) { return vrec_[v.idx()]; }
  detail::EdgeRecord& erec(EH e) { return erec_[e.idx()]; }
  detail::FaceRecord& frec(FH f) { return frec_[f.idx()]; }
  detail::Vec3 position(VH v) const { return detail::to_vec(points_[v.idx()]); }

  // Layers (surface_layers.cpp).
  VH weld_or_create(std::uint64_t id, const std::array<double, 3>& p, std::int64_t rank, std::size_t index);
  std::uint8_t border_bits(const std::array<double, 3>& p) const;
  void drop_isolated_vertices();

  // Queues.
  detail::EdgeGeometry geometry_of(HH h) const;
  void place(EH e);
  std::uint32_t stamp_of(EH e) const;
  // Moves e between the queues (EdgeQueues::move) and keeps its component's count of waiting
  // edges. `hold`: for a parked edge, where the open faces hold it back (none: not known; it is
  // placed again when the region changes).
  void set_state(EH e, detail::EdgeState state, double key, const Region::NearestFace* hold = nullptr);
  // After the region grew from `before`: places again the parked edges whose square of their face
  // the grown region no longer has open, the only ones the merge may free, and renumbers the
  // others' faces (surface_merge.cpp).
  void place_parked_again(const Region& before);
  // Finds where the faces hold back each parked edge for which it is not known (after
  // import_state).
  void find_parked_faces();
  // Puts e in Q at `cost` with its candidate position (evaluated now: the stamp is today's).
  void enqueue(EH e, double cost, const detail::Vec3& target, bool retried);
  detail::Pending& pending(EH e) { return queues_.pending(erec(e)); }
  // `known`: the edge's cost inputs when the caller has just read them (the retry reads them
  // otherwise).
  void try_collapse(EH e, double cost, const detail::Vec3& target, bool retried,
                    const detail::CostInputs* known = nullptr);
  // The distance bound the triangles around c would get (the E0 guarantee, collapse_distance.hpp).
  // The patch around h is read when `gathered` is false (then set): several positions of one
  // collapse share it, as long as nothing changes in between.
  double collapse_error(HH h, const detail::Vec3& target, bool& gathered);
  void collapse(HH h, const detail::Vec3& target, double cost, double error);
  void report_collapse(HH h, const detail::Vec3& target, double cost, double error);

  // Puts the edge ab back in its queue with its state, key and, in Q, candidate (surface_state.cpp).
  void restore_edge(VH a, VH b, const detail::StateEdge& edge, std::size_t index);

  // Dumping and compaction (surface_dump.cpp).
  void dump_component(std::int32_t root);
  void maybe_collect_garbage();
  // Compacts the mesh; `give_back` returns the room beyond the live elements (a surface set aside),
  // else the room stays for the layers still to come (a surface being swept: the room freed now
  // would be faulted in again within a few layers).
  void collect_garbage(bool give_back);

  volume::Geometry cube_;
  LatticeIds lattice_;
  Region region_;
  int axis_;
  SimplifyOptions options_;
  mesh::ComponentSink* sink_;
  CollapseObserver* observer_;
  std::array<double, 3> cube_hi_{};

  std::unique_ptr<detail::FrontRule> front_rule_;
  std::unique_ptr<detail::FaceRule> face_rule_;

  std::unique_ptr<detail::HalfedgeMesh> mesh_; // made empty, with any room a surface destroyed here left
  detail::VertexRecord* vrec_ = nullptr;
  detail::EdgeRecord* erec_ = nullptr;
  detail::FaceRecord* frec_ = nullptr;
  detail::HalfedgeMesh::Point* points_ = nullptr;
  detail::EdgeCost costs_; // the face terms' sums and the cost of each collapse

  detail::EdgeQueues queues_; // Q, W and the parked edges
  detail::ComponentTable components_;
  detail::IdMap previous_ids_; // ids of the last layer: the next one may repeat them
  detail::IdMap current_ids_;
  detail::VertexMarks marks_;
  detail::CollapseDistance distance_;
  detail::ComponentReader reader_;                   // reads a finished component out for dumping
  std::vector<std::int32_t> isolated_;               // vertices of the last layer that no triangle uses yet
  std::vector<std::array<double, 3>> new_positions_; // scratch: the vertices a layer creates

  double front_ = -std::numeric_limits<double>::infinity();
  std::int64_t last_rank_ = std::numeric_limits<std::int64_t>::min();
  std::size_t live_vertices_ = 0;
  std::size_t live_faces_ = 0;
  SimplifyCounters counters_;
};

} // namespace geotandem::tandem
