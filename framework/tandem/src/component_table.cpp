#include "component_table.hpp"

namespace geotandem::tandem::detail {

std::vector<std::int32_t> ComponentTable::compact() {
  std::vector<std::int32_t> map(records_.size(), -1);
  std::vector<ComponentRecord> kept;
  kept.reserve(alive_);
  for (std::size_t i = 0; i < records_.size(); ++i) {
    ComponentRecord& r = records_[i];
    if (r.parent == static_cast<std::int32_t>(i) && r.alive) {
      map[i] = static_cast<std::int32_t>(kept.size());
      kept.push_back(r);
      kept.back().parent = map[i];
    }
  }
  for (std::size_t i = 0; i < records_.size(); ++i)
    map[i] = map[static_cast<std::size_t>(find(static_cast<std::int32_t>(i)))];
  std::vector<std::int32_t> queue;
  for (std::int32_t c : maybe_finished_)
    if (map[static_cast<std::size_t>(c)] >= 0) queue.push_back(map[static_cast<std::size_t>(c)]);
  records_.swap(kept);
  for (ComponentRecord& r : records_)
    r.queued = false;
  maybe_finished_.clear();
  for (std::int32_t c : queue)
    requeue(c);
  return map;
}

} // namespace geotandem::tandem::detail
