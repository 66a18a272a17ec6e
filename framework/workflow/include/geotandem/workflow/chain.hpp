#pragma once
// A recipe's chain as data: the input cube, the attribute steps and the extraction, each with its
// plugin's name and version and every parameter, in a canonical JSON form. Another process (a
// worker of the manager/worker runtime) rebuilds the same attribute volume from it with
// open_chain_volume; its fingerprint identifies an extraction (state.json, stores). The format is
// documented in docs/chain-description.md.

#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geotandem/core/progress.hpp"
#include "geotandem/volume/volume.hpp"
#include "geotandem/workflow/recipe.hpp"
#include "geotandem/workflow/registry.hpp"

namespace geotandem::workflow {

struct ChainStep {
  std::string step;                          // the registry's name ("chaos", "extract", ...)
  std::string version;                       // the plugin's own version
  std::string as;                            // the result's name
  std::vector<std::string> inputs;           // earlier results; "input" is the cube
  std::map<std::string, std::string> params; // every parameter, as validated text
};

struct ChainDescription {
  static constexpr int format = 1; // of the JSON form
  // The input: {"file": ABSOLUTE PATH, "nan": "error"|"fill", "no_data": NUMBER?, "variable": NAME?,
  // "missing": "dead samples"?} or {"synthetic": {"kind", "shape", "seed", "snr"}, "nan": ...}
  // (docs/chain-description.md).
  nlohmann::json input;
  // The attribute steps the extraction reads, in chain order, then the extract step (last).
  std::vector<ChainStep> steps;

  const ChainStep& extract_step() const { return steps.back(); }
  // The extraction reads an attribute, not the input itself.
  bool reads_attribute() const { return !steps.empty() && extract_step().inputs != std::vector<std::string>{"input"}; }

  // Canonical JSON: keys sorted, parameters as text; equal chains give equal text.
  nlohmann::json to_json() const;
  // Throws FormatError naming what is missing or mistyped.
  static ChainDescription from_json(const nlohmann::json& json);
  // 16 hex digits (FNV-1a 64 of to_json().dump()): the identity of an extraction.
  std::string fingerprint() const;
};

// The chain of a validated recipe (input paths made absolute against its directory).
ChainDescription describe_chain(const Recipe& recipe, const PluginRegistry& plugins);

struct ChainVolumes {
  // The cube (a synth::SyntheticCube when synthetic). Under `nan: fill` with attributes, its missing
  // samples read as NaN: the attributes see them as 0 and the result masks them.
  std::shared_ptr<const volume::Volume> input;
  // The volume the extraction reads (lazy). When attributes are computed, each read of it fetches
  // the input for the box plus the chain's total halo once, and the attributes share that fetch
  // (src/shared_input.hpp): a synthetic input is generated once per read, not once per attribute.
  std::shared_ptr<const volume::Volume> result;
};

// Opens the input and builds the attribute steps as lazy volumes: nothing is computed and nothing
// is written. Every step is checked against `plugins`: known, of the right kind, of the same
// version, its parameters valid. Throws InvalidArgument naming the step, and what opening the input
// throws.
// `progress` (may be null) follows long work while the input opens (OpenOptions::progress).
ChainVolumes open_chain(const ChainDescription& description, const PluginRegistry& plugins,
                        Progress* progress = nullptr);
// open_chain(...).result.
std::shared_ptr<const volume::Volume> open_chain_volume(const ChainDescription& description,
                                                        const PluginRegistry& plugins);

// The validated values of a described step for `plugin` (every parameter of its spec).
ParamValues chain_step_values(const ChainStep& step, const Plugin& plugin);

} // namespace geotandem::workflow
