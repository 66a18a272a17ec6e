#pragma once
// The edges' queues and the state machine between them (the edge life cycle of collapser.hpp):
// Q, the candidates by cost, each with its Pending (position, stamp); W, the edges the front delays,
// in unit buckets of their lag key; and the edges the open faces park. An edge is in one queue at
// most. Its record (EdgeRecord) says which one and keeps its key; one slot array, shared by the
// three queues, gives its place there, so that no queue searches for an edge.
//
// The collapser decides where an edge goes (Collapser::place); this object only moves it and keeps the
// queues consistent with the records. move() is on the collapse loop's path: it is inline.

#include <cstdint>
#include <utility>
#include <vector>

#include "bucket_queue.hpp"
#include "geotandem/tandem/region.hpp"
#include "indexed_heap.hpp"
#include "parked_edges.hpp"
#include "working_mesh.hpp"

namespace geotandem::tandem::detail {

class EdgeQueues {
public:
  EdgeQueues() : candidates_(&slots_), delayed_(&slots_), parked_(&slots_) {}
  // The queues point at their shared slot array.
  EdgeQueues(const EdgeQueues&) = delete;
  EdgeQueues& operator=(const EdgeQueues&) = delete;

  // Slots for edges 0 .. edges - 1 (the mesh grew).
  void ensure_slots(std::size_t edges) {
    if (slots_.size() < edges) slots_.resize(edges, -1);
  }

  // Moves edge `item`, whose record is `r`, to `state` with `key`; an edge that stays in its queue
  // moves in place. A parked edge keeps where the open faces hold it back (`hold`; null: not
  // known). Returns whether the edge entered or left W, which changes its component's count of
  // waiting edges (ComponentTable::add_waiting).
  bool move(EdgeRecord& r, std::int32_t item, EdgeState state, double key, const Region::NearestFace* hold = nullptr) {
    const EdgeState old = r.state;
    if (old == state) {
      if (state == EdgeState::candidate) candidates_.update(item, key);
      if (state == EdgeState::delayed) {
        delayed_.erase(item, r.key);
        delayed_.push(item, key);
      }
      if (state == EdgeState::parked) hold_at(r, hold);
      r.key = key;
      return false;
    }
    switch (old) {
    case EdgeState::candidate:
      candidates_.erase(item);
      pending_.release(r.pending_or_square);
      break;
    case EdgeState::delayed: delayed_.erase(item, r.key); break;
    case EdgeState::parked: parked_.erase(item); break;
    case EdgeState::idle: break;
    }
    r.state = state;
    r.key = key;
    switch (state) {
    case EdgeState::candidate:
      candidates_.push(item, key);
      r.pending_or_square = pending_.acquire();
      break;
    case EdgeState::delayed: delayed_.push(item, key); break;
    case EdgeState::parked:
      parked_.add(item);
      hold_at(r, hold);
      break;
    case EdgeState::idle: break;
    }
    return waiting(old) != waiting(state);
  }

  // Q.
  bool has_candidates() const { return !candidates_.empty(); }
  // The cheapest candidate: its edge (item) and cost (key).
  const IndexedHeap::Entry& cheapest() const { return candidates_.top(); }
  // The candidate of an edge in Q.
  Pending& pending(const EdgeRecord& r) { return pending_[r.pending_or_square]; }
  const Pending& pending(const EdgeRecord& r) const { return pending_[r.pending_or_square]; }

  // W.
  std::size_t waiting_count() const { return delayed_.size() + parked_.size(); }
  // Appends to `bucket` the delayed edges of the lowest bucket when it may hold keys below `front`
  // (the caller checks each key); false when none can (BucketQueue::lowest_below).
  bool delayed_below(double front, std::vector<std::int32_t>& bucket) { return delayed_.lowest_below(front, bucket); }
  const std::vector<std::int32_t>& parked() const { return parked_.items(); }

  // Records where the open faces hold a parked edge back (EdgeRecord::face, pending_or_square).
  static void hold_at(EdgeRecord& r, const Region::NearestFace* hold) {
    if (hold && hold->index >= 0 && hold->index < kUnknownFace) {
      r.face = static_cast<std::uint16_t>(hold->index);
      r.pending_or_square = square_of(hold->at);
    } else {
      r.face = kUnknownFace;
      r.pending_or_square = kUnknownSquare;
    }
  }

  // A compaction renumbers the edges: forget_numbers() before (W's buckets go, and the candidates'
  // storage when Q is empty), rebuild() after, from the records that moved with their edges.
  // rebuild() alone also makes the queues what the records say.
  void forget_numbers() {
    delayed_.clear();
    pending_.release_storage();
  }
  // `give_back`: keep exactly the room the parked list needs (a surface set aside).
  void rebuild(const EdgeRecord* records, std::size_t edges, bool give_back) {
    std::vector<std::int32_t>(edges, -1).swap(slots_); // exact storage, as the mesh's
    std::vector<IndexedHeap::Entry> q;
    delayed_.clear();
    parked_.clear();
    for (std::size_t i = 0; i < edges; ++i) {
      const EdgeRecord& r = records[i];
      const auto item = static_cast<std::int32_t>(i);
      switch (r.state) {
      case EdgeState::candidate: q.push_back({r.key, item}); break;
      case EdgeState::delayed: delayed_.push(item, r.key); break;
      case EdgeState::parked: parked_.add(item); break; // its record keeps its face
      case EdgeState::idle: break;
      }
    }
    if (give_back) parked_.shrink_to_fit();
    candidates_.assign(std::move(q));
  }

private:
  std::vector<std::int32_t> slots_; // edge -> its place in Q, W or the parked list
  IndexedHeap candidates_;          // Q, by eps_alpha
  // The Pending of each edge in Q, at the index its record keeps: emptied with Q, its room given
  // back at a compaction with Q empty.
  PendingPool pending_;
  BucketQueue delayed_; // W, by lag key (unit buckets)
  ParkedEdges parked_;  // W, edges waiting for the region to grow
};

} // namespace geotandem::tandem::detail
