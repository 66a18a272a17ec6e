#pragma once
// The extraction step: a volume's isosurface, by the extended tandem algorithm, into a component
// store, with the run's statistics recorded in the store. Used by `geotandem extract` and by the
// extract step of recipes. Until the manager/worker runtime exists it runs in this process.

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/log.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::workflow {

enum class ExtractMode { tandem_dump, tandem, brute };
ExtractMode parse_extract_mode(const std::string& text);
const char* to_string(ExtractMode mode);

struct ExtractSettings {
  float iso = 0.0f;
  double max_error = 0.5;      // E0, voxels
  double isotropy = 0.4;       // alpha
  int axis = 0;                // 0 = i (inline), 1 = j, 2 = k
  std::int64_t block_size = 0; // leaf edge of the block tree, in cells (0: one block)
  ExtractMode mode = ExtractMode::tandem_dump;
  bool extended_time_lag = true;
  nlohmann::json parameters; // extra description recorded with the run (the recipe, the command)
  // The manager/worker runtime (extract_workers.cpp): with workers > 0 the blocks are extracted by
  // that many local worker processes running `worker_command` (e.g. {"/usr/bin/geotandem",
  // "worker"}), which rebuild the volume from `volume_description`. 0: in this process.
  std::size_t workers = 0;
  std::string volume_description;
  std::vector<std::string> worker_command;
};

struct ExtractResult {
  std::int64_t run = 0;
  std::uint64_t components = 0;      // committed by this run (new keys)
  std::uint64_t duplicates = 0;      // already in the store (a resumed run)
  std::uint64_t input_triangles = 0; // produced by marching cubes
  std::uint64_t peak_triangles = 0;  // most held in memory at a layer boundary
  std::uint64_t collapses = 0;
  std::vector<std::uint64_t> triangles_per_layer; // with blocks: every leaf's layers in tree order
  nlohmann::json blocks;                          // leaves, merges, seam collapses, bytes shipped, seconds per phase
  double seconds = 0.0;
  std::int64_t peak_rss_kb = 0;
  nlohmann::json statistics; // what was recorded in the store's run table
};

// Parses "i", "j", "k" (or 0, 1, 2); throws InvalidArgument otherwise.
int parse_axis(const std::string& text);

// Extracts the isosurface of `volume` at settings.iso into `store` (which must be writable and
// have the volume's geometry), as one block or, with settings.block_size > 0, through the block
// tree (tandem::extract_blocks). Components are committed as they finish, so an interrupted run
// keeps them; running again commits the rest (keys are deterministic). Throws what the volume,
// the algorithm and the store throw, and Cancelled.
ExtractResult extract_to_store(const volume::Volume& volume, store::ComponentStore& store,
                               const ExtractSettings& settings, Logger& log, Progress& progress,
                               const CancelToken& cancel);

// The same through the manager/worker runtime (settings.workers local workers; block_size 0 means
// 64). Called by extract_to_store when settings.workers > 0. Throws InvalidArgument when the
// volume description or the worker command is missing.
ExtractResult extract_with_workers(const volume::Volume& volume, store::ComponentStore& store,
                                   const ExtractSettings& settings, Logger& log, Progress& progress,
                                   const CancelToken& cancel);

// Peak resident set size of this process so far, in KiB (VmHWM).
std::int64_t peak_rss_kb();

} // namespace geotandem::workflow
