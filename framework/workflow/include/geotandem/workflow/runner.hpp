#pragma once
// Running a validated recipe: input cube, attribute chain (lazy, fused block by block into the
// extraction), extraction into the store, component steps, exports, report. Every step's
// fingerprint is kept in OUTPUT/state.json; a rerun with the same inputs and parameters reuses
// finished steps instead of recomputing them.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/log.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/workflow/recipe.hpp"
#include "geotandem/workflow/registry.hpp"

namespace geotandem::workflow {

struct WorkflowSettings {
  bool dry_run = false; // build and check the whole chain, print the plan, compute nothing
  bool fresh = false;   // discard a previous run's store in the output directory
  std::function<std::unique_ptr<Progress>()> progress; // a new reporter per step; null: none
  // The command line of a worker process without --connect and --token (e.g. {"/usr/bin/geotandem",
  // "worker"}). With it, a recipe's `execution: {scheduler: local, workers: N}` (N >= 2) extracts
  // with N local workers; empty: in this process.
  std::vector<std::string> worker_command;
};

struct RunOutcome {
  std::string output_dir;
  std::string store_dir;
  std::string report;             // empty on a dry run
  std::uint64_t components = 0;   // in the store after extraction
  std::uint64_t kept = 0;         // in the last selection
  bool extraction_reused = false; // the store already held this extraction
};

// Throws InvalidArgument (the output holds another extraction: pass fresh), and what each step
// throws; components committed before a failure stay in the store and state.json says which steps
// finished.
RunOutcome run_workflow(const Recipe& recipe, const PluginRegistry& plugins, const WorkflowSettings& settings,
                        Logger& log, const CancelToken& cancel);

} // namespace geotandem::workflow
