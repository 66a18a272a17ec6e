#pragma once
// A coarse uniform grid over the cube listing, per cell, the items (bodies, bubbles) whose
// influence box touches it, so that a box read only evaluates the items near it.

#include <cstdint>
#include <vector>

#include "geotandem/volume/box.hpp"

namespace geotandem::synth::detail {

class ItemGrid {
public:
  ItemGrid(const volume::Index3& shape, std::int64_t cell);
  // `influence` is clipped to the cube; empty boxes are ignored.
  void add(std::uint32_t item, const volume::Box& influence);
  // Items whose influence touches `box`, sorted, without duplicates.
  std::vector<std::uint32_t> query(const volume::Box& box) const;

private:
  volume::Box cells_of(const volume::Box& box) const;
  std::size_t cell_index(std::int64_t ci, std::int64_t cj, std::int64_t ck) const;

  volume::Index3 shape_;
  std::int64_t cell_;
  volume::Index3 count_{};
  std::vector<std::vector<std::uint32_t>> cells_;
};

} // namespace geotandem::synth::detail
