#pragma once
// The collapser: what the working surface does with its records. It keeps the queues (Q, the
// candidates by cost; W, the edges the front delays and those the open faces park), the cost of
// each collapse (EdgeCost), the distance bound (CollapseDistance), and collapses. The records
// themselves are the storage's (surface_storage.hpp), read through it each time.
//
// Edge life cycle (place()): an edge whose lag key is not below the front is delayed; else, if
// the open faces forbid it, parked; else its candidate is computed and it enters Q, or stays idle
// when the shape error exceeds E0. Any change of a or b re-places the edge. A popped candidate is
// collapsed unless the link condition, the distance bound or the flip test refuses it (then it
// stays idle until its neighbourhood changes; it gets one retry at the best of a, b and the
// midpoint).

#include <array>
#include <limits>
#include <memory>
#include <vector>

#include "collapse_distance.hpp"
#include "collapse_ops.hpp"
#include "constraints.hpp"
#include "edge_cost.hpp"
#include "edge_queues.hpp"
#include "geotandem/tandem/simplify.hpp"
#include "surface_state.hpp"
#include "surface_storage.hpp"

namespace geotandem::tandem::detail {

class Collapser {
public:
  // `storage` and `region` (the surface's, which may grow) outlive this object.
  Collapser(SurfaceStorage& storage, const Region& region, int axis, const SimplifyOptions& options,
            const std::array<double, 3>& cube_hi, CollapseObserver* observer);
  Collapser(const Collapser&) = delete;
  Collapser& operator=(const Collapser&) = delete;

  const SimplifyOptions& options() const { return options_; }
  double front() const { return front_; }
  void set_front(double front) { front_ = front; }
  SimplifyCounters& counters() { return counters_; }
  const SimplifyCounters& counters() const { return counters_; }
  EdgeCost& costs() { return costs_; }
  const EdgeCost& costs() const { return costs_; }
  const EdgeQueues& queues() const { return queues_; }
  // Scratch marks over the vertices, shared with whoever reads the mesh between collapses.
  VertexMarks& marks() { return marks_; }
  CollapseObserver* observer() const { return observer_; }
  void set_observer(CollapseObserver* observer) { observer_ = observer; }

  // The storage grew (storage.end_append()): room for the new edges and vertices here.
  void grown() {
    queues_.ensure_slots(storage_.mesh().n_edges());
    marks_.ensure(storage_.mesh().n_vertices());
  }
  // A compaction renumbers the edges and vertices: forget_numbers() before
  // (SurfaceStorage::compact()), renumbered() after, which rebuilds the queues from the records that
  // moved with their edges and the face terms' sums from scratch.
  void forget_numbers() { queues_.forget_numbers(); }
  void renumbered(bool give_back);

  // New triangles joined the surface (a layer): their face terms go into their corners' sums, and
  // every edge of theirs waits in W (delay(k)).
  void delay_new_faces(const std::vector<FH>& faces);
  // The face terms of triangles that joined the surface (the other side of a merge).
  void add_faces(const std::vector<FH>& faces);
  // Moves the front to `front` (not back) and places the delayed edges it passed (activate(k)).
  void activate(double front);
  // Places every parked edge again (the region changed).
  void place_parked();
  // After the region grew from `before`: places again the parked edges whose square of their face
  // the grown region no longer has open, the only ones a merge may free, and renumbers the
  // others' faces.
  void place_parked_again(const Region& before);
  // Finds where the faces hold back each parked edge for which it is not known (after an import).
  void find_parked_faces();
  // Collapses candidates until Q is empty.
  void simplify(const CancelToken* cancel);

  // Puts the edge ab back in its queue with its state, key and, in Q, candidate (an import or the
  // other side of a merge); throws DataError when ab is not an edge.
  void restore_edge(VH a, VH b, const StateEdge& edge, std::size_t index);
  // Moves e between the queues (EdgeQueues::move) and keeps its component's count of waiting
  // edges. `hold`: for a parked edge, where the open faces hold it back (none: not known; it is
  // placed again when the region changes).
  void set_state(EH e, EdgeState state, double key, const Region::NearestFace* hold = nullptr);

private:
  EdgeGeometry geometry_of(HH h) const;
  void place(EH e);
  std::uint32_t stamp_of(EH e) const;
  // Puts e in Q at `cost` with its candidate position (evaluated now: the stamp is today's).
  void enqueue(EH e, double cost, const Vec3& target, bool retried);
  Pending& pending(EH e) { return queues_.pending(storage_.edge(e)); }
  // `known`: the edge's cost inputs when the caller has just read them (the retry reads them
  // otherwise).
  void try_collapse(EH e, double cost, const Vec3& target, bool retried, const CostInputs* known = nullptr);
  // The distance bound the triangles around c would get (the E0 guarantee, collapse_distance.hpp).
  // The patch around h is read when `gathered` is false (then set): several positions of one
  // collapse share it, as long as nothing changes in between.
  double collapse_error(HH h, const Vec3& target, bool& gathered);
  void collapse(HH h, const Vec3& target, double cost, double error);
  void report_collapse(HH h, const Vec3& target, double cost, double error);

  VertexRecord& vrec(VH v) { return mesh_.vertex_records()[v.idx()]; }
  const VertexRecord& vrec(VH v) const { return mesh_.vertex_records()[v.idx()]; }
  EdgeRecord& erec(EH e) { return mesh_.edge_records()[e.idx()]; }

  SurfaceStorage& storage_;
  HalfedgeMesh& mesh_; // the storage's: the same object for the storage's life
  const Region& region_;
  SimplifyOptions options_;
  std::unique_ptr<FrontRule> front_rule_;
  std::unique_ptr<FaceRule> face_rule_;
  EdgeCost costs_;    // the face terms' sums and the cost of each collapse
  EdgeQueues queues_; // Q, W and the parked edges
  VertexMarks marks_;
  CollapseDistance distance_;
  SimplifyCounters counters_;
  double front_ = -std::numeric_limits<double>::infinity();
  CollapseObserver* observer_;
};

} // namespace geotandem::tandem::detail
