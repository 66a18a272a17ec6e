#pragma once
// What every worker of a run must agree on, sent by the manager in SETUP as JSON: how to rebuild
// the input volume (a description the application's VolumeFactory understands), the extraction
// options, and the store's directory.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "geotandem/tandem/tandem.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::runtime {

// Rebuilds the input volume in a worker from the description the manager sends (JSON text).
// Provided by the application (geotandem worker): a cube file, a synthetic cube, a recipe's input
// with its attribute chain. Throws what opening the volume throws.
using VolumeFactory = std::function<std::shared_ptr<const volume::Volume>(const std::string& description_json)>;

struct RunSettings {
  std::string volume;           // the description (JSON text) handed to the VolumeFactory
  std::string store;            // the store's directory; each worker writes shards/<token>.gts
  std::int64_t block_size = 64; // leaf edge of the block tree, in cells (at least 8)
  float iso = 0.0f;
  bool below = false; // side below: inside means value <= iso (sent only when true)
  int axis = 0;
  double max_error = 0.5;
  double isotropy = 0.4;
  bool extended_time_lag = true;
  bool dump = true;                    // tandem with dumping (off: plain tandem)
  bool brute = false;                  // each leaf by brute force
  std::int64_t run = 0;                // the store's run id recorded with every component
  std::uint64_t chunk_bytes = 1 << 20; // partial surfaces travel in chunks of at most this size

  std::string to_json() const;
  // Throws ProtocolError when the text is not a settings object of this version.
  static RunSettings from_json(const std::string& text);
  tandem::TandemOptions tandem_options() const;
};

} // namespace geotandem::runtime
