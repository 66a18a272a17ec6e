#pragma once
// A 4-ary min-heap of items (edge indices) with in-place key updates and removal. Measured while
// choosing the design (ALGORITHM.md): replacing a lazy std::priority_queue with this was the
// largest single gain of the collapse loop. Each item's position lives in a slot array shared with
// the other queues (an edge is in at most one queue at a time), so no hash lookups are needed.

#include <cassert>
#include <cstdint>
#include <vector>

namespace geotandem::tandem::detail {

class IndexedHeap {
public:
  struct Entry {
    double key;
    std::int32_t item;
  };

  // `slots` maps item -> position in this heap; it must be large enough for every pushed item.
  explicit IndexedHeap(std::vector<std::int32_t>* slots) : slots_(slots) {}

  bool empty() const { return heap_.empty(); }
  std::size_t size() const { return heap_.size(); }
  const Entry& top() const { return heap_.front(); }
  const std::vector<Entry>& entries() const { return heap_; }
  double key(std::int32_t item) const { return heap_[static_cast<std::size_t>(slot(item))].key; }

  void push(std::int32_t item, double key) {
    heap_.push_back({key, item});
    set_slot(item, static_cast<std::int32_t>(heap_.size() - 1));
    up(heap_.size() - 1);
  }
  // Changes the key of an item that is in the heap.
  void update(std::int32_t item, double key) {
    const auto i = static_cast<std::size_t>(slot(item));
    const double old = heap_[i].key;
    heap_[i].key = key;
    if (key < old)
      up(i);
    else
      down(i);
  }
  void pop() { erase_at(0); }
  void erase(std::int32_t item) { erase_at(static_cast<std::size_t>(slot(item))); }
  void clear() {
    for (const Entry& e : heap_)
      set_slot(e.item, -1);
    heap_.clear();
  }
  // Replaces the content wholesale (after a garbage collection), then restores the heap order.
  void assign(std::vector<Entry> entries) {
    heap_ = std::move(entries);
    for (std::size_t i = 0; i < heap_.size(); ++i)
      set_slot(heap_[i].item, static_cast<std::int32_t>(i));
    if (heap_.size() > 1)
      for (std::size_t i = (heap_.size() - 2) / kArity + 1; i-- > 0;)
        down(i);
  }

private:
  static constexpr std::size_t kArity = 4;

  std::int32_t slot(std::int32_t item) const { return (*slots_)[static_cast<std::size_t>(item)]; }
  void set_slot(std::int32_t item, std::int32_t s) { (*slots_)[static_cast<std::size_t>(item)] = s; }

  void erase_at(std::size_t i) {
    assert(i < heap_.size());
    set_slot(heap_[i].item, -1);
    const Entry last = heap_.back();
    heap_.pop_back();
    if (i == heap_.size()) return;
    const double old = heap_[i].key;
    heap_[i] = last;
    set_slot(last.item, static_cast<std::int32_t>(i));
    if (last.key < old)
      up(i);
    else
      down(i);
  }
  void up(std::size_t i) {
    const Entry e = heap_[i];
    while (i > 0) {
      const std::size_t parent = (i - 1) / kArity;
      if (!(e.key < heap_[parent].key)) break;
      heap_[i] = heap_[parent];
      set_slot(heap_[i].item, static_cast<std::int32_t>(i));
      i = parent;
    }
    heap_[i] = e;
    set_slot(e.item, static_cast<std::int32_t>(i));
  }
  void down(std::size_t i) {
    const Entry e = heap_[i];
    const std::size_t n = heap_.size();
    for (;;) {
      const std::size_t first = i * kArity + 1;
      if (first >= n) break;
      std::size_t best = first;
      const std::size_t end = first + kArity < n ? first + kArity : n;
      for (std::size_t c = first + 1; c < end; ++c)
        if (heap_[c].key < heap_[best].key) best = c;
      if (!(heap_[best].key < e.key)) break;
      heap_[i] = heap_[best];
      set_slot(heap_[i].item, static_cast<std::int32_t>(i));
      i = best;
    }
    heap_[i] = e;
    set_slot(e.item, static_cast<std::int32_t>(i));
  }

  std::vector<Entry> heap_;
  std::vector<std::int32_t>* slots_;
};

} // namespace geotandem::tandem::detail
