#pragma once
// The manager's writes to the store's index (it alone writes it): the component entries its
// workers report, each key committed once whatever retries happen. A key already in the index is
// a duplicate, unless its record reads back damaged: then the worker's new record replaces it (a
// rerun repairs a damaged store, as the in-process extraction does). Internal to the runtime.
#include <cstdint>
#include <vector>

#include "geotandem/core/cancel.hpp"
#include "geotandem/store/store.hpp"

namespace geotandem::runtime::detail {

class ComponentCommitter {
public:
  explicit ComponentCommitter(store::ComponentStore& store) : store_(store) {}

  // Commits the entries (records already synced by the worker). Throws IoError as
  // ComponentStore::commit.
  void commit(std::vector<store::IndexEntry> entries);

  std::uint64_t added() const { return added_; }
  std::uint64_t duplicates() const { return duplicates_; }
  std::uint64_t repaired() const { return repaired_; }
  // The first keys repaired (at most 20): a rerun names what it wrote again.
  const std::vector<std::uint64_t>& repaired_keys() const { return repaired_keys_; }

  // The number of indexed records that do not read back intact (checked one by one).
  std::uint64_t count_damaged(const CancelToken& cancel) const;

private:
  store::ComponentStore& store_;
  std::uint64_t added_ = 0, duplicates_ = 0, repaired_ = 0;
  std::vector<std::uint64_t> repaired_keys_;
};

} // namespace geotandem::runtime::detail
