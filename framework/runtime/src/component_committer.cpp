// The manager's commits to the index (component_committer.hpp).
#include "component_committer.hpp"

#include <algorithm>

#include "geotandem/store/check.hpp"

namespace geotandem::runtime::detail {

void ComponentCommitter::commit(std::vector<store::IndexEntry> entries) {
  std::vector<store::IndexEntry> rows;
  rows.reserve(entries.size());
  std::uint64_t replacing = 0;
  // One lookup for the batch: a key is rarely there already (a retried task, a resumed run).
  std::vector<std::uint64_t> keys;
  keys.reserve(entries.size());
  for (const store::IndexEntry& e : entries)
    keys.push_back(e.key);
  std::vector<std::uint64_t> present = store_.present(keys);
  std::sort(present.begin(), present.end());
  for (store::IndexEntry& e : entries) {
    if (!std::binary_search(present.begin(), present.end(), e.key)) {
      rows.push_back(std::move(e));
      continue;
    }
    if (const std::optional<store::ComponentRow> row = store_.find(e.key)) {
      if (!store::verify_component(store_, *row)) {
        ++duplicates_;
        continue;
      }
      e.replace = true; // its record is damaged: this one takes its place
      ++replacing;
      if (repaired_keys_.size() < 20) repaired_keys_.push_back(e.key);
    }
    rows.push_back(std::move(e));
  }
  if (rows.empty()) return;
  const std::size_t n = store_.commit(rows);
  // A replaced row counts among the rows written; a key twice in one batch is written once.
  added_ += n - std::min<std::size_t>(n, replacing);
  repaired_ += replacing;
  duplicates_ += rows.size() - n;
}

std::uint64_t ComponentCommitter::count_damaged(const CancelToken& cancel) const {
  std::uint64_t damaged = 0;
  for (const store::ComponentRow& row : store_.query()) {
    cancel.throw_if_cancelled();
    if (store::verify_component(store_, row)) ++damaged;
  }
  return damaged;
}

} // namespace geotandem::runtime::detail
