#include "item_grid.hpp"

#include <algorithm>
#include <stdexcept>

namespace geotandem::synth::detail {

ItemGrid::ItemGrid(const volume::Index3& shape, std::int64_t cell) : shape_(shape), cell_(cell) {
  for (int a = 0; a < 3; ++a)
    count_[a] = (shape[a] + cell - 1) / cell;
}

volume::Box ItemGrid::cells_of(const volume::Box& box) const {
  const volume::Box clipped = box.intersection(volume::Box::of_shape(shape_));
  volume::Box cells;
  if (clipped.empty()) return cells;
  for (int a = 0; a < 3; ++a) {
    cells.lo[a] = clipped.lo[a] / cell_;
    cells.hi[a] = (clipped.hi[a] - 1) / cell_ + 1;
  }
  return cells;
}

std::size_t ItemGrid::cell_index(std::int64_t ci, std::int64_t cj, std::int64_t ck) const {
  return static_cast<std::size_t>((ci * count_[1] + cj) * count_[2] + ck);
}

void ItemGrid::add(std::uint32_t item, const volume::Box& influence) {
  if (!first_.empty()) throw std::logic_error("ItemGrid::add after seal()");
  const volume::Box cells = cells_of(influence);
  for (auto ci = cells.lo[0]; ci < cells.hi[0]; ++ci)
    for (auto cj = cells.lo[1]; cj < cells.hi[1]; ++cj)
      for (auto ck = cells.lo[2]; ck < cells.hi[2]; ++ck)
        added_.emplace_back(cell_index(ci, cj, ck), item);
}

void ItemGrid::seal() {
  // A counting sort by cell.
  first_.assign(static_cast<std::size_t>(count_[0] * count_[1] * count_[2]) + 1, 0);
  for (const auto& [cell, item] : added_)
    ++first_[cell + 1];
  for (std::size_t c = 1; c < first_.size(); ++c)
    first_[c] += first_[c - 1];
  items_.resize(added_.size());
  std::vector<std::size_t> next(first_.begin(), first_.end() - 1);
  for (const auto& [cell, item] : added_)
    items_[next[cell]++] = item;
  std::vector<std::pair<std::size_t, std::uint32_t>>().swap(added_);
}

std::vector<std::uint32_t> ItemGrid::query(const volume::Box& box) const {
  if (first_.empty()) throw std::logic_error("ItemGrid::query before seal()");
  std::vector<std::uint32_t> items;
  const volume::Box cells = cells_of(box);
  for (auto ci = cells.lo[0]; ci < cells.hi[0]; ++ci)
    for (auto cj = cells.lo[1]; cj < cells.hi[1]; ++cj)
      for (auto ck = cells.lo[2]; ck < cells.hi[2]; ++ck) {
        const std::size_t c = cell_index(ci, cj, ck);
        items.insert(items.end(), items_.begin() + static_cast<std::ptrdiff_t>(first_[c]),
                     items_.begin() + static_cast<std::ptrdiff_t>(first_[c + 1]));
      }
  std::sort(items.begin(), items.end());
  items.erase(std::unique(items.begin(), items.end()), items.end());
  return items;
}

} // namespace geotandem::synth::detail
