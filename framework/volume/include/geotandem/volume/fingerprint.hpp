#pragma once
// What identifies an input's content, cheaply: for a file, its size, modification time and an
// xxh-style checksum of sampled blocks (the first and last 64 KiB and 62 blocks of 4 KiB spread
// evenly between); for a directory (Zarr), the same over its files; for anything else (a
// synthetic cube, an attribute chain), its canonical description. Two fingerprints are equal when
// the input is, barring an edit of unsampled bytes that keeps the size and the modification time.

#include <string>

#include <nlohmann/json.hpp>

namespace geotandem::volume {

// `source` is a path or a description (Volume::source()). Never throws for a missing file: the
// description is used then.
nlohmann::json input_fingerprint(const std::string& source);

} // namespace geotandem::volume
