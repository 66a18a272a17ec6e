#pragma once
// The checksum of one index row (docs/store-format.md, "Row checksums"): XXH64 (seed 0) over the
// row's values in column order, each integer as 8 little-endian bytes, each REAL as the 8 bytes
// of its IEEE 754 double (-0.0 and NaN as 0.0, as SQLite gives them back), a NULL run as one 0 byte (1 and the id
// otherwise), cut_faces as its length and text. A measure flipped in index.sqlite (a disk fault, a hand edit) no longer
// matches, and the component reads as damaged, as a damaged record does.

#include <cstdint>
#include <optional>
#include <string>

#include "geotandem/mesh/component.hpp"
#include "geotandem/store/shard.hpp"

namespace geotandem::store::detail {

// The vertex and triangle counts are the location's (those of `stats` are not stored).
std::uint64_t row_checksum(std::uint64_t key, const RecordLocation& location, const mesh::ComponentStats& stats,
                           const std::optional<std::int64_t>& run, bool samples = false);

} // namespace geotandem::store::detail
