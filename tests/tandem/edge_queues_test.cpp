// Unit tests of the edges' queues: the indexed heap (Q), the parked list, and the state machine
// that moves edges between them (EdgeQueues).
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <map>
#include <random>

#include "edge_queues.hpp"
#include "geotandem/tandem/region.hpp"
#include "indexed_heap.hpp"
#include "parked_edges.hpp"

namespace geotandem::tandem {
namespace {

// ------------------------------------------------------------------------------------- heap

TEST(IndexedHeap, MatchesAnOrderedReferenceUnderUpdatesAndRemovals) {
  constexpr int kItems = 2000;
  std::vector<std::int32_t> slots(kItems, -1);
  detail::IndexedHeap heap(&slots);
  std::map<std::int32_t, double> reference;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> key(0.0, 100.0);
  std::uniform_int_distribution<std::int32_t> item(0, kItems - 1);
  for (int step = 0; step < 20000; ++step) {
    const std::int32_t i = item(rng);
    const int op = static_cast<int>(rng() % 4);
    const bool present = reference.count(i) > 0;
    if (!present && op < 3) {
      const double k = key(rng);
      heap.push(i, k);
      reference[i] = k;
    } else if (present && op == 0) {
      const double k = key(rng);
      heap.update(i, k);
      reference[i] = k;
    } else if (present) {
      heap.erase(i);
      reference.erase(i);
      EXPECT_EQ(slots[static_cast<std::size_t>(i)], -1);
    }
    ASSERT_EQ(heap.size(), reference.size());
    if (!reference.empty()) {
      double smallest = std::numeric_limits<double>::infinity();
      for (const auto& [it, k] : reference)
        smallest = std::min(smallest, k);
      ASSERT_EQ(heap.top().key, smallest);
      ASSERT_EQ(reference.at(heap.top().item), smallest);
    }
  }
  // Popping gives non-decreasing keys; assign() rebuilds the same content.
  std::vector<detail::IndexedHeap::Entry> entries = heap.entries();
  std::reverse(entries.begin(), entries.end());
  detail::IndexedHeap other(&slots);
  heap.clear();
  other.assign(entries);
  double last = -1.0;
  std::size_t popped = 0;
  while (!other.empty()) {
    EXPECT_GE(other.top().key, last);
    last = other.top().key;
    other.pop();
    ++popped;
  }
  EXPECT_EQ(popped, reference.size());
}

// ------------------------------------------------------------------------------------- parked edges and the state
// machine

TEST(ParkedEdges, KeepsItsSlotsThroughRemovals) {
  // Against a reference list with the same swap-with-last removals.
  std::vector<std::int32_t> slots(400, -1);
  detail::ParkedEdges parked(&slots);
  std::vector<std::int32_t> reference;
  std::mt19937 rng(11);
  for (std::int32_t item = 0; item < 400; ++item) {
    parked.add(item);
    reference.push_back(item);
  }
  for (int n = 0; n < 150; ++n) {
    const auto k = static_cast<std::size_t>(rng() % reference.size());
    const std::int32_t item = reference[k];
    parked.erase(item);
    reference[k] = reference.back();
    reference.pop_back();
    EXPECT_EQ(slots[static_cast<std::size_t>(item)], -1);
  }
  ASSERT_EQ(parked.items(), reference);
  for (std::size_t k = 0; k < reference.size(); ++k)
    ASSERT_EQ(slots[static_cast<std::size_t>(reference[k])], static_cast<std::int32_t>(k));
  parked.shrink_to_fit();
  EXPECT_EQ(parked.items(), reference);
  parked.clear();
  EXPECT_EQ(parked.size(), 0u);
}

// The queues against a reference model (each edge's state and key in a map): random moves between
// the four states, in place and across, then the rebuild a compaction does from the records.
TEST(EdgeQueues, FollowTheRecordsThroughEveryMoveAndARebuild) {
  using detail::EdgeState;
  constexpr std::int32_t n = 300;
  detail::EdgeQueues queues;
  queues.ensure_slots(n);
  std::vector<detail::EdgeRecord> records(n);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> keys(0.0, 50.0);
  const Region::NearestFace hold{3, 0.5, {7.5, 2.25}};
  // Checks Q's cheapest, W's size, every parked edge's face and every candidate's Pending
  // against the records.
  const auto check = [&](const std::vector<double>& marks) {
    std::size_t waiting = 0, candidates = 0, parked = 0;
    double cheapest = std::numeric_limits<double>::infinity();
    for (std::int32_t e = 0; e < n; ++e) {
      const detail::EdgeRecord& r = records[static_cast<std::size_t>(e)];
      if (detail::waiting(r.state)) ++waiting;
      if (r.state == EdgeState::parked) {
        ++parked;
        ASSERT_EQ(r.face, 3u);
        ASSERT_EQ(r.pending_or_square, detail::square_of({7.5, 2.25}));
      }
      if (r.state == EdgeState::candidate) {
        ++candidates;
        cheapest = std::min(cheapest, r.key);
        ASSERT_EQ(queues.pending(r).target[0], marks[static_cast<std::size_t>(e)]) << "edge " << e;
      }
    }
    ASSERT_EQ(queues.waiting_count(), waiting);
    ASSERT_EQ(queues.parked().size(), parked);
    ASSERT_EQ(queues.has_candidates(), candidates > 0);
    if (candidates > 0) {
      ASSERT_EQ(queues.cheapest().key, cheapest);
      ASSERT_EQ(records[static_cast<std::size_t>(queues.cheapest().item)].key, cheapest);
    }
  };
  std::vector<double> marks(n, 0.0); // what each candidate's Pending holds
  for (int step = 0; step < 5000; ++step) {
    const auto e = static_cast<std::int32_t>(rng() % n);
    detail::EdgeRecord& r = records[static_cast<std::size_t>(e)];
    const auto state = static_cast<EdgeState>(rng() % 4);
    const bool was_waiting = detail::waiting(r.state);
    const bool crossed = queues.move(r, e, state, state == EdgeState::idle ? 0.0 : keys(rng), &hold);
    ASSERT_EQ(crossed, was_waiting != detail::waiting(state));
    ASSERT_EQ(r.state, state);
    if (state == EdgeState::candidate) {
      marks[static_cast<std::size_t>(e)] = step;
      queues.pending(r).target = {static_cast<double>(step), 0.0, 0.0};
    }
    if (step % 500 == 0) check(marks);
  }
  check(marks);
  // Every candidate leaves Q in key order, and the delayed edges below a front come out of W.
  double last = -1.0;
  while (queues.has_candidates()) {
    const auto top = queues.cheapest();
    ASSERT_GE(top.key, last);
    last = top.key;
    queues.move(records[static_cast<std::size_t>(top.item)], top.item, EdgeState::idle, 0.0);
  }
  queues.forget_numbers();
  queues.rebuild(records.data(), records.size(), true);
  check(marks);
  std::vector<std::int32_t> below;
  ASSERT_TRUE(queues.delayed_below(60.0, below));
  for (std::int32_t e : below)
    ASSERT_EQ(records[static_cast<std::size_t>(e)].state, EdgeState::delayed);
  // An unknown hold marks the parked edge to be placed again.
  const auto idle = std::find_if(records.begin(), records.end(),
                                 [](const detail::EdgeRecord& r) { return r.state == EdgeState::idle; });
  ASSERT_NE(idle, records.end());
  queues.move(*idle, static_cast<std::int32_t>(idle - records.begin()), EdgeState::parked, 1.0);
  EXPECT_EQ(idle->face, detail::kUnknownFace);
  EXPECT_EQ(idle->pending_or_square, detail::kUnknownSquare);
  // The rebuild alone (no forget_numbers() before) leaves no stale entry behind.
  idle->state = EdgeState::delayed;
  queues.rebuild(records.data(), records.size(), false);
  ASSERT_EQ(queues.waiting_count(),
            static_cast<std::size_t>(std::count_if(
                records.begin(), records.end(), [](const detail::EdgeRecord& r) { return detail::waiting(r.state); })));
}

} // namespace
} // namespace geotandem::tandem
