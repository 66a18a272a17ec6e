#pragma once
// Recipes: what a geophysicist writes. A recipe names an input cube, a chain of steps, the outputs
// and how to execute. It is validated completely before any work starts; every error names the
// file, line and column and, for unknown keys and names, suggests the nearest valid one.
// The full schema is in docs/recipe-schema.md.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geotandem/volume/geometry.hpp"
#include "geotandem/volume/segy_options.hpp"
#include "geotandem/workflow/plugin.hpp"
#include "geotandem/workflow/registry.hpp"

namespace geotandem::workflow {

struct Where {
  long line = 0; // 1-based; 0 when unknown (a --set override)
  long column = 0;
};

struct InputSpec {
  // Exactly one of: a file path, or a synthetic cube.
  std::string file;     // relative paths are relative to the recipe's directory
  std::string variable; // for multidimensional files with several arrays
  std::string nan = "error";
  // input.no_data: samples equal to it are missing, as NaN samples are (SEG-Y and raw cubes cannot
  // declare their null; -999.25 is common).
  std::optional<double> no_data;
  // SEG-Y trace header fields: input.segy.{inline,crossline,x,y}_{byte,type} and
  // input.segy.coordinate_scalar.
  volume::SegyOptions segy;
  // input.crs: the CRS of the map coordinates as given (an EPSG code or a WKT), checked through
  // OSR while the recipe is read; it replaces what the file says. nullopt: the file's, if any.
  std::string crs_text;
  std::optional<volume::Crs> crs;
  bool synthetic = false;
  std::string synthetic_kind = "seismic"; // analytic | seismic
  std::int64_t shape[3] = {160, 160, 128};
  std::uint64_t seed = 1;
  double snr = 4.0;
  Where where;
};

struct StepSpec {
  StepKind kind = StepKind::attribute; // the step's own kind, from the registry
  std::string name;                    // the step's name in the registry ("chaos", "extract", ...)
  std::string as;                      // the name later steps use for its result (default: name)
  std::vector<std::string> inputs;     // names of earlier results; "input" is the recipe's cube
  int arity = 1;                       // inputs an attribute needs
  ParamValues params;                  // every parameter, defaults filled in
  Where where;
};

struct ExportSpec {
  std::string format;    // ply | obj | vtp | ts
  std::string selection; // a selection written by a component step; empty: the last one
  std::string path;      // relative to the output directory
  bool per_component = false;
  bool caps = true; // keep the caps of bodies cut by the cube's border
};

struct OutputSpec {
  std::string directory;       // relative paths are relative to the working directory (CWD)
  std::string store = "store"; // relative to directory
  std::string report = "report.html";
  std::string attribute_file; // when set, the final attribute cube is written there too
  // When set, the label cube of the last selection (workflow/label_cube.hpp) is written there
  // after the component steps, with its table beside it (PATH.bodies.csv, PATH.bodies.json).
  std::string labels_file;
  std::vector<ExportSpec> exports;
};

struct ResourceSpec {
  int cpus_per_worker = 1;
  std::int64_t memory_mb = 0; // 0: the scheduler's default
  std::int64_t walltime_s = 0;
  std::string queue;
  std::string account;
  std::vector<std::string> extra_args;
};

struct ExecutionSpec {
  std::string scheduler = "local"; // local | slurm | lsf
  int workers = 1;
  // False when the recipe does not say: a local run then gets one worker per core (at most one
  // per block; see default_worker_count), a cluster scheduler `workers`.
  bool workers_given = false;
  ResourceSpec resources;
  std::string bind; // where the manager listens: "" (loopback), an interface or an address
  // The partial surfaces waiting in the manager for their merge: MiB held in memory before they
  // wait on disk (-1: the runtime's default).
  std::int64_t relay_memory_mb = -1;
};

struct Recipe {
  std::string path;     // the recipe file
  std::string base_dir; // its directory, for relative paths
  InputSpec input;
  std::vector<StepSpec> steps;
  OutputSpec output;
  // The steps the output section asks for, run after `steps`: one export step per entry of
  // output.exports, then the report step.
  std::vector<StepSpec> finish;
  ExecutionSpec execution;
  // The recipe after defaults and overrides, as JSON: shown in reports, hashed for reruns.
  nlohmann::json canonical;
};

// Reads and validates a recipe. `overrides` are "dotted.path=value" strings from --set (for
// example "execution.workers=4", "steps.extract.iso=0.4", "input.synthetic.seed=3"); a bad override
// is reported as coming from --set. Throws InvalidArgument / IoError with file, line and column.
Recipe load_recipe(const std::string& path, const PluginRegistry& plugins,
                   const std::vector<std::string>& overrides = {});

// The same, from text (tests); `name` stands for the file name in messages.
Recipe parse_recipe(const std::string& text, const std::string& name, const PluginRegistry& plugins,
                    const std::vector<std::string>& overrides = {});

} // namespace geotandem::workflow
