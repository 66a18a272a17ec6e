#pragma once
// A coarse uniform grid over the cube listing, per cell, the items (bodies, bubbles) whose
// influence box touches it, so that a box read only evaluates the items near it.

#include <cstdint>
#include <utility>
#include <vector>

#include "geotandem/volume/box.hpp"

namespace geotandem::synth::detail {

class ItemGrid {
public:
  ItemGrid(const volume::Index3& shape, std::int64_t cell);
  // `influence` is clipped to the cube; empty boxes are ignored. Only before seal().
  void add(std::uint32_t item, const volume::Box& influence);
  // Packs the cells' lists into one array, what query() reads (a list per cell cost a quarter of a
  // million allocations on a 1024^3 analytic cube). No add() after it.
  void seal();
  // Items whose influence touches `box`, sorted, without duplicates. Only after seal() (throws
  // std::logic_error before).
  std::vector<std::uint32_t> query(const volume::Box& box) const;

private:
  volume::Box cells_of(const volume::Box& box) const;
  std::size_t cell_index(std::int64_t ci, std::int64_t cj, std::int64_t ck) const;

  volume::Index3 shape_;
  std::int64_t cell_;
  volume::Index3 count_{};
  std::vector<std::pair<std::size_t, std::uint32_t>> added_; // (cell, item), until seal()
  std::vector<std::size_t> first_; // cell c's items: items_[first_[c], first_[c + 1]); empty until seal()
  std::vector<std::uint32_t> items_;
};

} // namespace geotandem::synth::detail
