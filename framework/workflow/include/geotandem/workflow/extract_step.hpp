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
#include "geotandem/tandem/simplify.hpp"
#include "geotandem/volume/volume.hpp"
#include "geotandem/workflow/plugin.hpp"

namespace geotandem::workflow {

enum class ExtractMode { tandem_dump, tandem, brute };
ExtractMode parse_extract_mode(const std::string& text);
const char* to_string(ExtractMode mode);

// The smallest leaf edge of the block tree, in cells (0 means one block). The block tree and the
// merges are correct down to 1 cell (leaves of 1 to 7 cells give the same component keys as one
// block on a 48^3 analytic cube), so this bound is about cost, not correctness: every leaf and
// merge has a fixed overhead, and 2-cell leaves took 25 times as long as 16-cell ones there.
// Recipes and `geotandem extract` refuse smaller blocks at validation.
inline constexpr std::int64_t min_block_size = 8;

// The defaults stated here are the only ones: the extract step's parameters (extract_params(),
// used by recipes and by `geotandem extract`) take theirs from a default ExtractSettings, whose
// simplification defaults come from tandem::SimplifyOptions.
struct ExtractSettings {
  float iso = 0.0f;
  // Which side of iso is inside a body (issue 54): above (value >= iso, the default) or below
  // (value <= iso; tandem::McOptions::below).
  bool below = false;
  double max_error = tandem::SimplifyOptions{}.max_error; // E0, voxels
  double isotropy = tandem::SimplifyOptions{}.isotropy;   // alpha
  int axis = 0;                                           // 0 = i (inline), 1 = j, 2 = k
  std::int64_t block_size = 128;                          // leaf edge of the block tree, in cells (0: one block)
  ExtractMode mode = ExtractMode::tandem_dump;
  bool extended_time_lag = tandem::SimplifyOptions{}.extended_time_lag;
  nlohmann::json parameters; // extra description recorded with the run (the recipe, the command)
  // The manager/worker runtime (extract_workers.cpp): with workers > 0 the blocks are extracted by
  // that many local worker processes running `worker_command` (e.g. {"/usr/bin/geotandem",
  // "worker"}), which rebuild the volume from `volume_description`. 0: in this process.
  std::size_t workers = 0;
  std::string volume_description;
  std::vector<std::string> worker_command;
  // Where the workers run: "local" (child processes) or a cluster scheduler ("slurm", "lsf"), with
  // the recipe's execution.resources as JSON (cpus_per_worker, memory_mb, walltime_s, queue,
  // account, extra_args). See extract_workers.cpp.
  std::string scheduler = "local";
  nlohmann::json resources;
  std::string bind; // where the manager listens (runtime::manager_bind_endpoint); "": loopback
  // MiB of partial surfaces the manager holds for their merges before they wait on disk (-1: the
  // runtime's default, runtime::ManagerOptions::relay_memory).
  std::int64_t relay_memory_mb = -1;
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

// Parses "above" or "below" (true for below); throws InvalidArgument otherwise.
bool parse_side(const std::string& text);
inline const char* side_text(bool below) {
  return below ? "below" : "above";
}

// Parses "i", "j", "k" (or 0, 1, 2); throws InvalidArgument otherwise.
int parse_axis(const std::string& text);

// The extraction's declared parameters (iso, max_error, isotropy, axis, block_size, mode,
// extended_time_lag), defaults from ExtractSettings{}.
const std::vector<ParamSpec>& extract_params();
// What parse_param cannot see alone: block_size is 0 or at least min_block_size. Throws
// InvalidArgument naming the parameter.
void check_extract_params(const ParamValues& values);
// The settings of validated values (every parameter of extract_params()).
ExtractSettings extract_settings(const ParamValues& values);

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

// Extracts the isosurface of `volume` at settings.iso into `store` (which must be writable and
// have the volume's geometry), as one block or, with settings.block_size > 0, through the block
// tree (tandem::extract_blocks). Components are committed as they finish, so an interrupted run
// keeps them; running again commits the rest (keys are deterministic). Throws what the volume,
// the algorithm and the store throw, and Cancelled.
ExtractResult extract_to_store(const volume::Volume& volume, store::ComponentStore& store,
                               const ExtractSettings& settings, Logger& log, Progress& progress,
                               const CancelToken& cancel);

// The parameters a run records in the store, with its identity (what decides the components: the
// store refuses to mix runs of different identities). Shared by both routes.
nlohmann::json extract_run_parameters(const volume::Volume& volume, const ExtractSettings& settings);
// Logs and records a warning when a run extracted nothing.
void warn_if_empty(ExtractResult& result, const ExtractSettings& settings, Logger& log);

// The number of local workers an extraction gets when nobody says: one per core, no more than
// there are blocks; 0 (this process) for the whole cube as one block or a tree of one leaf, which
// one process does as fast.
std::size_t default_worker_count(const volume::Geometry& geometry, std::int64_t block_size);

// The same through the manager/worker runtime (settings.workers local workers; block_size 0 means
// 64). Called by extract_to_store when settings.workers > 0. Throws InvalidArgument when the
// volume description or the worker command is missing.
ExtractResult extract_with_workers(const volume::Volume& volume, store::ComponentStore& store,
                                   const ExtractSettings& settings, Logger& log, Progress& progress,
                                   const CancelToken& cancel);

// Peak resident set size of this process so far, in KiB (VmHWM).
std::int64_t peak_rss_kb();

} // namespace geotandem::workflow
