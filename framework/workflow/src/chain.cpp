// The chain description: built from a recipe, written and read as JSON, and rebuilt into lazy
// volumes through the registry.

#include "geotandem/workflow/chain.hpp"

#include <cstdio>
#include <filesystem>
#include <limits>

#include "geotandem/core/error.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "geotandem/volume/crs.hpp"
#include "geotandem/volume/io.hpp"
#include "shared_input.hpp"

namespace fs = std::filesystem;

namespace geotandem::workflow {
namespace {

// The CRS a description's input names (an EPSG code or a WKT, checked again through OSR).
volume::Crs crs_of(const nlohmann::json& in) {
  return volume::parse_crs(in.at("crs").get<std::string>());
}

// `missing_as_nan`: under `nan: fill`, the missing samples read as NaN rather than the lowest float
// (the attributes then see them as dead samples and the result masks them: open_chain).
// `below`: the extraction takes the low side, so a filled sample must be the highest float to
// stay outside every body.
std::shared_ptr<const volume::Volume> open_input(const nlohmann::json& in, bool missing_as_nan, bool below,
                                                 Progress* progress) {
  if (in.contains("synthetic")) {
    const auto& s = in.at("synthetic");
    const auto shape = s.at("shape").get<std::vector<std::int64_t>>();
    std::unique_ptr<synth::SyntheticCube> cube;
    if (s.at("kind").get<std::string>() == "analytic") {
      synth::AnalyticOptions o;
      o.shape = {shape.at(0), shape.at(1), shape.at(2)};
      o.seed = s.at("seed").get<std::uint64_t>();
      cube = synth::make_analytic(o);
    } else {
      synth::SeismicOptions o;
      o.shape = {shape.at(0), shape.at(1), shape.at(2)};
      o.seed = s.at("seed").get<std::uint64_t>();
      o.snr = s.at("snr").get<double>();
      cube = synth::make_seismic(o);
    }
    if (in.contains("crs")) return volume::with_crs(std::shared_ptr<const volume::Volume>(std::move(cube)), crs_of(in));
    return std::shared_ptr<const volume::Volume>(std::move(cube));
  }
  volume::OpenOptions options;
  options.nan_policy = volume::parse_nan_policy(in.value("nan", "error"));
  if (missing_as_nan)
    options.fill_value = std::numeric_limits<float>::quiet_NaN();
  else if (below)
    options.fill_value = std::numeric_limits<float>::max();
  if (in.contains("no_data")) options.no_data = static_cast<float>(in.at("no_data").get<double>());
  options.variable = in.value("variable", "");
  if (in.contains("segy")) options.segy = volume::segy_options_from_json(in["segy"]);
  // Not part of the chain's identity: the runner adds it to the workers' copy only.
  options.reopen_hint = in.value("reopen_hint", "");
  // Nor is the CRS (it changes no sample and no component): the runner adds the recipe's to the
  // workers' copy, so that the workers' volume says what the manager's does.
  if (in.contains("crs")) options.crs = crs_of(in);
  options.progress = progress;
  return std::shared_ptr<const volume::Volume>(volume::open_volume(in.at("file").get<std::string>(), options));
}

// Whether the attributes of a chain see the input's missing samples as dead samples (0) and its
// result masks them (open_chain): a file read with `nan: fill` under attributes.
bool dead_samples(const ChainDescription& chain) {
  return chain.input.contains("file") && chain.input.value("nan", "error") == "fill" && chain.reads_attribute();
}

[[noreturn]] void bad(const std::string& what) {
  throw FormatError("chain description: " + what, {},
                    "write it with ChainDescription::to_json (docs/chain-description.md)");
}

} // namespace

nlohmann::json ChainDescription::to_json() const {
  nlohmann::json j;
  j["format"] = format;
  j["input"] = input;
  j["steps"] = nlohmann::json::array();
  for (const auto& s : steps)
    j["steps"].push_back(
        {{"step", s.step}, {"version", s.version}, {"as", s.as}, {"inputs", s.inputs}, {"params", s.params}});
  return j;
}

ChainDescription ChainDescription::from_json(const nlohmann::json& j) {
  if (!j.is_object()) bad("not a JSON object");
  if (j.value("format", 0) != format)
    bad("format " + (j.contains("format") ? j["format"].dump() : std::string("missing")) + ", this geotandem reads " +
        std::to_string(format));
  ChainDescription d;
  if (!j.contains("input") || !j["input"].is_object()) bad("no 'input' object");
  const auto& in = j["input"];
  if (in.contains("file") == in.contains("synthetic")) bad("the input needs exactly one of 'file' or 'synthetic'");
  if (in.contains("file") && !in["file"].is_string()) bad("input.file is not a string");
  if (in.contains("no_data") && !in["no_data"].is_number()) bad("input.no_data is not a number");
  if (in.contains("crs") && !in["crs"].is_string()) bad("input.crs is not a string");
  if (in.contains("synthetic")) {
    const auto& s = in["synthetic"];
    if (!s.is_object() || !s.contains("kind") || !s.contains("shape") || !s.contains("seed") || !s.contains("snr") ||
        !s["shape"].is_array() || s["shape"].size() != 3)
      bad("input.synthetic needs kind, shape (three sizes), seed and snr");
  }
  d.input = in;
  if (!j.contains("steps") || !j["steps"].is_array() || j["steps"].empty()) bad("no 'steps' list");
  try {
    for (const auto& s : j["steps"]) {
      ChainStep step;
      step.step = s.at("step").get<std::string>();
      step.version = s.at("version").get<std::string>();
      step.as = s.at("as").get<std::string>();
      step.inputs = s.at("inputs").get<std::vector<std::string>>();
      step.params = s.at("params").get<std::map<std::string, std::string>>();
      d.steps.push_back(std::move(step));
    }
  } catch (const nlohmann::json::exception& e) {
    bad(std::string("a step is malformed: ") + e.what());
  }
  return d;
}

std::string ChainDescription::fingerprint() const {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : to_json().dump()) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

ChainDescription describe_chain(const Recipe& recipe, const PluginRegistry& plugins) {
  ChainDescription d;
  d.input = recipe.canonical.at("input");
  // The CRS changes no sample and no component: it is the runner's (run_workflow gives it to the
  // extraction's volume), not the chain's, whose fingerprint stays that of the recipe without it.
  d.input.erase("crs");
  if (!recipe.input.synthetic) {
    fs::path path = recipe.input.file;
    if (path.is_relative() && !recipe.base_dir.empty()) path = fs::path(recipe.base_dir) / path;
    d.input["file"] = fs::absolute(path).lexically_normal().string();
  }
  for (const auto& s : recipe.steps) {
    if (s.kind != StepKind::attribute && s.kind != StepKind::extract) break;
    ChainStep step{s.name, plugins.get(s.name).version(), s.as, s.inputs, {}};
    for (const auto& [k, v] : s.params)
      step.params[k] = v.text;
    // The extraction's side (issue 54) is said only when it is not the default: the chains of
    // recipes written before it keep their text, so their fingerprints, states and stores.
    if (s.kind == StepKind::extract && step.params.count("side") && step.params["side"] == "above")
      step.params.erase("side");
    d.steps.push_back(std::move(step));
    if (s.kind == StepKind::extract) break;
  }
  if (d.steps.empty() || plugins.get(d.steps.back().step).kind() != StepKind::extract)
    throw InvalidArgument("the recipe's chain has no extract step", {recipe.path});
  // Said in the description, so that its fingerprint differs from that of the same recipe before
  // the attributes saw dead samples (they saw the fill's lowest float): such a store is not reused.
  if (dead_samples(d)) d.input["missing"] = "dead samples";
  return d;
}

ParamValues chain_step_values(const ChainStep& step, const Plugin& plugin) {
  ParamValues values;
  for (const auto& [name, text] : step.params) {
    bool known = false;
    for (const auto& spec : plugin.params())
      known = known || spec.name == name;
    if (!known)
      throw InvalidArgument("step '" + step.step + "' has no parameter '" + name + "'", {plugin.origin()},
                            "the description was written for another version of the plugin");
  }
  for (const auto& spec : plugin.params()) {
    auto it = step.params.find(spec.name);
    if (it != step.params.end())
      values[spec.name] = parse_param(spec, it->second);
    else if (spec.default_value)
      values[spec.name] = parse_param(spec, *spec.default_value);
    else
      throw InvalidArgument("step '" + step.step + "' needs parameter '" + spec.name + "'", {}, spec.help);
  }
  plugin.check(values);
  return values;
}

ChainVolumes open_chain(const ChainDescription& description, const PluginRegistry& plugins, Progress* progress) {
  if (description.steps.empty()) throw InvalidArgument("the chain description has no steps");
  // Every step is checked before the input is opened: cheap refusals first.
  std::vector<std::pair<const Plugin*, ParamValues>> resolved;
  std::map<std::string, int> results{{"input", 0}};
  for (std::size_t n = 0; n < description.steps.size(); ++n) {
    const ChainStep& step = description.steps[n];
    const Plugin& plugin = plugins.get(step.step);
    const bool last = n + 1 == description.steps.size();
    const StepKind wanted = last ? StepKind::extract : StepKind::attribute;
    if (plugin.kind() != wanted)
      throw InvalidArgument("step " + std::to_string(n + 1) + " of the chain description, '" + step.step + "', is " +
                                (plugin.kind() == StepKind::attribute ? "an " : "a ") + to_string(plugin.kind()) +
                                "; expected " + (last ? "the extraction" : "an attribute"),
                            {plugin.origin()});
    if (plugin.version() != step.version)
      throw InvalidArgument("step '" + step.step + "' was described with version " + step.version +
                                ", but the registry holds version " + plugin.version(),
                            {plugin.origin()}, "install the same plugin version on every machine of the run");
    for (const auto& name : step.inputs)
      if (!results.count(name))
        throw InvalidArgument("step '" + step.step + "' of the chain description reads '" + name +
                              "', which no earlier step produces");
    if (step.inputs.size() != static_cast<std::size_t>(plugin.input_count()))
      throw InvalidArgument("step '" + step.step + "' takes " + std::to_string(plugin.input_count()) +
                            " input(s), got " + std::to_string(step.inputs.size()));
    resolved.emplace_back(&plugin, chain_step_values(step, plugin));
    results[step.as] = 0;
  }
  ChainVolumes out;
  // Missing samples filled (`nan: fill`) under attributes: the attributes see dead samples (0), and
  // the result is the lowest float wherever the input is missing (shared_input.hpp, DeadSamples).
  // Read directly by the extraction, they are the lowest float from the input itself.
  const bool dead = dead_samples(description);
  const ParamValues& extract = resolved.back().second;
  const bool below = extract.count("side") && extract.at("side").text == "below";
  out.input = open_input(description.input, dead, below, progress);
  // The attributes read the input through one shared fetch per read of the result (shared_input.hpp).
  auto shared = std::make_shared<const detail::SharedInput>(out.input);
  std::shared_ptr<const volume::Volume> seen = shared;
  if (dead) seen = std::make_shared<const detail::DeadSamples>(shared);
  std::map<std::string, std::shared_ptr<const volume::Volume>> volumes{{"input", seen}};
  for (std::size_t n = 0; n < description.steps.size(); ++n) {
    const ChainStep& step = description.steps[n];
    std::vector<std::shared_ptr<const volume::Volume>> inputs;
    for (const auto& name : step.inputs)
      inputs.push_back(volumes.at(name));
    if (n + 1 == description.steps.size())
      out.result = inputs.front() == seen
                       ? out.input
                       : std::make_shared<const detail::PrefetchingResult>(
                             inputs.front(), shared, dead,
                             below ? std::numeric_limits<float>::max() : std::numeric_limits<float>::lowest());
    else
      volumes[step.as] = resolved[n].first->make_attribute(std::move(inputs), resolved[n].second);
  }
  return out;
}

std::shared_ptr<const volume::Volume> open_chain_volume(const ChainDescription& description,
                                                        const PluginRegistry& plugins) {
  return open_chain(description, plugins).result;
}

} // namespace geotandem::workflow
