#pragma once
// Integrity check of a store: every index row is verified against its row checksum and every
// indexed record is read back and verified (magic, version, length, counts, key, xxh64 checksum). Damaged components
// are listed by key; a rerun of the same extraction re-extracts them (LocalSink replaces a damaged record), and `store
// export
// --skip-damaged` exports the others.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/store/store.hpp"

namespace geotandem::store {

struct DamagedComponent {
  std::uint64_t key = 0;
  RecordLocation location;
  std::string problem; // the reader's message: what is wrong, in which shard, at which offset
};

struct CheckReport {
  std::uint64_t checked = 0;
  // Rows without a row checksum (written before row checksums: their measures are not verified,
  // only their records); all of them when the index has no row_checksum column at all.
  std::uint64_t rows_without_checksum = 0;
  bool index_has_row_checksums = true;
  std::vector<DamagedComponent> damaged; // in key order
  double seconds = 0;
};

// The problem of one indexed record, or std::nullopt when it reads back intact.
std::optional<std::string> verify_component(const ComponentStore& store, const ComponentRow& row);

// Verifies every component of the store. Throws Cancelled.
CheckReport check_store(const ComponentStore& store, Progress& progress, const CancelToken& cancel);

} // namespace geotandem::store
