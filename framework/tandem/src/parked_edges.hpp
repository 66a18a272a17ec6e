#pragma once
// W's other part: the edges the open faces hold back (parked). Each edge's record names the face
// that holds it back (EdgeRecord::face), so a merge places again only the edges whose face it
// closed (surface_merge.cpp) without reading where any edge lies; the list itself holds items.

#include <cstdint>
#include <vector>

namespace geotandem::tandem::detail {

class ParkedEdges {
public:
  // `slots` maps item -> position in the list (shared with the other queues).
  explicit ParkedEdges(std::vector<std::int32_t>* slots) : slots_(slots) {}

  std::size_t size() const { return items_.size(); }
  const std::vector<std::int32_t>& items() const { return items_; }

  void add(std::int32_t item) {
    if (items_.size() == items_.capacity()) // a quarter more, not twice: the list can be long
      items_.reserve(items_.size() + items_.size() / 4 + 64);
    (*slots_)[static_cast<std::size_t>(item)] = static_cast<std::int32_t>(items_.size());
    items_.push_back(item);
  }
  void erase(std::int32_t item) {
    const auto slot = static_cast<std::size_t>((*slots_)[static_cast<std::size_t>(item)]);
    items_[slot] = items_.back();
    (*slots_)[static_cast<std::size_t>(items_[slot])] = static_cast<std::int32_t>(slot);
    items_.pop_back();
    (*slots_)[static_cast<std::size_t>(item)] = -1;
  }
  void clear() { items_.clear(); }
  // Keeps exactly the room the list needs (a compaction that gives storage back).
  void shrink_to_fit() { items_.shrink_to_fit(); }

private:
  std::vector<std::int32_t>* slots_;
  std::vector<std::int32_t> items_;
};

} // namespace geotandem::tandem::detail
