#pragma once
// W's other part: the edges the open faces hold back (parked), with where each one's ball is
// (midpoint and radius, as the face rule reads them). A merge closes only the faces the new
// blocks touch, so only an edge whose ball reaches those blocks can be freed: near() finds them
// from these few floats instead of reading every parked edge's vertices, which on a surface that
// aggregates a large part of the cube was most of the cost of a merge (docs/algorithm.md).

#include <cstdint>
#include <vector>

#include "geotandem/volume/box.hpp"

namespace geotandem::tandem::detail {

class ParkedEdges {
public:
  // An edge's ball: its midpoint and the radius the face rule tests (rad(), which is at least
  // half the edge's length), in index coordinates.
  struct Spot {
    float x = 0.0f, y = 0.0f, z = 0.0f, radius = 0.0f;
  };

  // `slots` maps item -> position in the list (shared with the other queues).
  explicit ParkedEdges(std::vector<std::int32_t>* slots) : slots_(slots) {}

  std::size_t size() const { return items_.size(); }
  const std::vector<std::int32_t>& items() const { return items_; }

  void add(std::int32_t item, const Spot& spot) {
    if (items_.size() == items_.capacity()) { // a quarter more, not twice: the list can be long
      const std::size_t room = items_.size() + items_.size() / 4 + 64;
      items_.reserve(room);
      spots_.reserve(room);
    }
    (*slots_)[static_cast<std::size_t>(item)] = static_cast<std::int32_t>(items_.size());
    items_.push_back(item);
    spots_.push_back(spot);
  }
  // The edge moved (it is placed again and stays parked).
  void update(std::int32_t item, const Spot& spot) {
    spots_[static_cast<std::size_t>((*slots_)[static_cast<std::size_t>(item)])] = spot;
  }
  void erase(std::int32_t item) {
    const auto slot = static_cast<std::size_t>((*slots_)[static_cast<std::size_t>(item)]);
    items_[slot] = items_.back();
    spots_[slot] = spots_.back();
    (*slots_)[static_cast<std::size_t>(items_[slot])] = static_cast<std::int32_t>(slot);
    items_.pop_back();
    spots_.pop_back();
    (*slots_)[static_cast<std::size_t>(item)] = -1;
  }
  void clear() {
    items_.clear();
    spots_.clear();
  }
  // Keeps exactly the room the list needs (a compaction that gives storage back).
  void shrink_to_fit() {
    items_.shrink_to_fit();
    spots_.shrink_to_fit();
  }

  // The items, in list order, whose ball grown by `margin` meets the closed box of cells `cells`
  // (coordinates [lo, hi] on each axis).
  void near(const volume::Box& cells, double margin, std::vector<std::int32_t>& out) const;

private:
  std::vector<std::int32_t>* slots_;
  std::vector<std::int32_t> items_;
  std::vector<Spot> spots_;
};

} // namespace geotandem::tandem::detail
