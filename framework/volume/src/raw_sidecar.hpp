#pragma once
// The JSON sidecar of a raw cube, FILE.raw.json: its keys are listed in docs/formats-segy-raw.md.
#include <string>

#include "geotandem/volume/geometry.hpp"

namespace geotandem::volume::detail {

// The sidecar's path for a raw data file.
inline std::string raw_sidecar_of(const std::string& path) {
  return path + ".json";
}

// Reads and checks a sidecar; every error names the file, and the line and column for bad JSON.
Geometry read_raw_sidecar(const std::string& sidecar);

// The sidecar's text for a cube of geometry `g`.
std::string raw_sidecar_text(const Geometry& g);

} // namespace geotandem::volume::detail
