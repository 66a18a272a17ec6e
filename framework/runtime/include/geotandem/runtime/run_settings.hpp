#pragma once
// What every worker of a run must agree on, sent by the manager in SETUP as JSON: how to rebuild
// the input volume (a description the application's VolumeFactory understands), the extraction
// options (one value, tandem::ExtractionOptions, in its own codec), and the store's directory.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "geotandem/tandem/extraction_options.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::runtime {

// Rebuilds the input volume in a worker from the description the manager sends (JSON text).
// Provided by the application (geotandem worker): a cube file, a synthetic cube, a recipe's input
// with its attribute chain. Throws what opening the volume throws.
using VolumeFactory = std::function<std::shared_ptr<const volume::Volume>(const std::string& description_json)>;

struct RunSettings {
  std::string volume; // the description (JSON text) handed to the VolumeFactory
  std::string store;  // the store's directory; each worker writes shards/<token>.gts
  // The extraction's options as the user gave them, unchanged (block_size 0: the whole cube is one
  // block). The manager builds its block tree with tandem::leaf_size(), every worker its loop with
  // tandem::loop_options().
  tandem::ExtractionOptions extraction;
  std::int64_t run = 0;                // the store's run id recorded with every component
  std::uint64_t chunk_bytes = 1 << 20; // partial surfaces travel in chunks of at most this size

  // {"version", "volume", "store", "extraction": tandem::to_json(extraction), "run", "chunk_bytes"}.
  std::string to_json() const;
  // Throws ProtocolError when the text is not a settings object of this version, or its extraction
  // options are not valid ones (tandem::options_from_json).
  static RunSettings from_json(const std::string& text);
};

} // namespace geotandem::runtime
