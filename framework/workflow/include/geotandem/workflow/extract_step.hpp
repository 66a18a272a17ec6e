#pragma once
// The extraction step: a volume's isosurface, by the extended tandem algorithm, into a component
// store, with the run's statistics recorded in the store. Used by `geotandem extract`, Python's
// geotandem.extract and the extract step of recipes, in this process or through the manager/worker
// runtime.

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/log.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/tandem/extraction_options.hpp"
#include "geotandem/tandem/simplify.hpp"
#include "geotandem/volume/volume.hpp"
#include "geotandem/workflow/plugin.hpp"
#include "geotandem/workflow/recipe.hpp"

namespace geotandem::workflow {

// The extraction's options are one value owned by the tandem library (extraction_options.hpp): its
// declarations, defaults and JSON codec. These names are the workflow's for them.
using tandem::ExtractionOptions;
using tandem::ExtractMode;
using tandem::min_block_size;
using tandem::parse_axis;
using tandem::parse_extract_mode;
using tandem::to_string;

// Where an extraction runs and what its run records besides the options: the typed execution
// context a command, the Python module or the recipe runner hands to the extract step.
struct ExecutionContext {
  // Recorded with the run in the store: the recipe and its chain (recipe, chain,
  // chain_fingerprint, input_content), or the command and its cube (command, cube, and how the
  // file is read: no_data, variable, segy). Its "input_content", "chain", "no_data", "variable"
  // and "segy" join the run's identity (extract_run_parameters).
  nlohmann::json record = nlohmann::json::object();
  // The manager/worker runtime (extract_workers.cpp): with workers > 0 the blocks are extracted by
  // that many worker processes running `worker_command` (e.g. {"/usr/bin/geotandem", "worker"}),
  // which rebuild the volume from `volume_description`. 0: in this process.
  std::size_t workers = 0;
  std::string volume_description;
  std::vector<std::string> worker_command;
  // Where the workers run and with what (the recipe's execution section; its defaults for a
  // command): scheduler, resources, bind, relay_memory_mb. Its `workers` is not read here.
  ExecutionSpec execution;
};

struct ExtractResult {
  std::int64_t run = 0;
  std::uint64_t components = 0; // committed by this run (new keys)
  std::uint64_t duplicates = 0; // already in the store (a resumed run)
  // Damaged components of the store (store check) written again, and the first of their keys.
  std::uint64_t repaired = 0;
  std::vector<std::uint64_t> repaired_keys;
  std::uint64_t peak_triangles = 0; // most held in memory at a layer boundary
  // Every counter of the collapse loop, of the whole surface: input_triangles (made by marching
  // cubes), collapses, cost evaluations, refusals by reason (rejected_distance is what the E0
  // guarantee refused).
  tandem::SimplifyCounters counters;
  std::vector<std::uint64_t> triangles_per_layer; // with blocks: every leaf's layers in tree order
  nlohmann::json blocks;                          // leaves, merges, seam collapses, bytes shipped, seconds per phase
  double seconds = 0.0;
  std::int64_t peak_rss_kb = 0;
  nlohmann::json statistics; // what was recorded in the store's run table
};

// The extraction's declared parameters: tandem::extraction_params().
const std::vector<ParamSpec>& extract_params();

// Throws InvalidArgument unless the cube has at least two samples along each axis (marching cubes
// needs one cell; a single inline, crossline or time slice has none). `source` names the cube in
// the error (its file). Called before anything is written, by the commands and the runner, and
// again by extract_to_store.
void require_cells(const volume::Geometry& geometry, const std::string& source);

// The input cube read by blocks from a copy when its file's chunks make reads by blocks decode
// each chunk many times over (Volume::use_block_copy; docs/formats-gdal.md, "Chunks"): makes or
// reuses the copy in `directory` and logs it. Returns the copy's path, empty when the input needs
// none. A copy that cannot be written (a full disk) is a warning, and the file is read as it is.
// Called by the commands and the runner before the extraction, and remove_input_copy after it.
std::string copy_input_for_blocks(const volume::Volume& input, const std::string& directory, Logger& log,
                                  Progress& progress, const CancelToken& cancel);
void remove_input_copy(const std::string& path, Logger& log);

// Extracts the isosurface of `volume` at options.iso into `store` (which must be writable and
// have the volume's geometry), as one block or, with options.block_size > 0, through the block
// tree (tandem::extract_blocks). Components are committed as they finish, so an interrupted run
// keeps them; running again commits the rest (keys are deterministic). Throws what the volume,
// the algorithm and the store throw, and Cancelled.
ExtractResult extract_to_store(const volume::Volume& volume, store::ComponentStore& store,
                               const ExtractionOptions& options, const ExecutionContext& context, Logger& log,
                               Progress& progress, const CancelToken& cancel);

// The parameters a run records in the store, with its identity (what decides the components: the
// store refuses to mix runs of different identities). Shared by both routes.
nlohmann::json extract_run_parameters(const volume::Volume& volume, const ExtractionOptions& options,
                                      const ExecutionContext& context);
// Logs and records a warning when a run extracted nothing.
void warn_if_empty(ExtractResult& result, const ExtractionOptions& options, const ExecutionContext& context,
                   Logger& log);

// The number of local workers an extraction gets when nobody says: one per core, no more than
// there are blocks; 0 (this process) for the whole cube as one block or a tree of one leaf, which
// one process does as fast.
std::size_t default_worker_count(const volume::Geometry& geometry, std::int64_t block_size);

// The same through the manager/worker runtime (context.workers workers; block_size 0: the whole
// cube is one block, extracted by one worker). Called by extract_to_store when context.workers > 0.
// Throws InvalidArgument when the volume description or the worker command is missing.
ExtractResult extract_with_workers(const volume::Volume& volume, store::ComponentStore& store,
                                   const ExtractionOptions& options, const ExecutionContext& context, Logger& log,
                                   Progress& progress, const CancelToken& cancel);

// Peak resident set size of this process so far, in KiB (VmHWM).
std::int64_t peak_rss_kb();

} // namespace geotandem::workflow
