// The extraction's options, declared once (extraction_options.hpp): the field table, and what is
// read from it (parameters, the JSON codec, the loop's configuration).
#include "geotandem/tandem/extraction_options.hpp"

#include <algorithm>
#include <cstdlib>
#include <optional>

#include "geotandem/core/error.hpp"
#include "geotandem/core/suggest.hpp"

namespace geotandem::tandem {
namespace {

constexpr const char* kOwner = "extraction options";

// A declaration with a unit; its default is set from ExtractionOptions{} (make_fields()).
ParamSpec declare(std::string name, ParamType type, std::string help, std::string unit = {},
                  std::optional<double> lo = {}, std::optional<double> hi = {}, std::vector<std::string> choices = {}) {
  ParamSpec s = param_spec(std::move(name), type, std::nullopt, std::move(help), lo, hi, std::move(choices));
  s.unit = std::move(unit);
  return s;
}

// The options. A default is not written here: it is the member initialiser's (defaults() below).
std::vector<ExtractionField> make_fields() {
  using O = ExtractionOptions;
  std::vector<ExtractionField> fields;
  ParamSpec iso =
      declare("iso", ParamType::real, "isovalue: samples >= iso (side above) or <= iso (side below) are inside a body");
  iso.single_precision = true; // compared with float samples: beyond the float range is refused, not inf
  fields.push_back(member_param(std::move(iso), &O::iso));
  fields.push_back(choice_param(declare("side", ParamType::choice,
                                        "which side of iso is inside a body: above (value >= iso) or below (value <= "
                                        "iso: low coherence, low impedance)",
                                        {}, {}, {}, {"above", "below"}),
                                &O::side));
  fields.push_back(
      member_param(declare("max_error", ParamType::real,
                           "E0: the simplified surface stays within E0 of the full-resolution one (guaranteed)",
                           "voxels", 1e-6, 100.0),
                   &O::max_error));
  fields.push_back(member_param(
      declare("isotropy", ParamType::real, "alpha, weight of triangle shape against surface fidelity", {}, 0.0, 1.0),
      &O::isotropy));
  fields.push_back(
      choice_param(declare("axis", ParamType::choice, "extraction axis: i (inline), j (crossline) or k (sample)", {},
                           {}, {}, {"i", "j", "k"}),
                   &O::axis));
  fields.push_back(
      member_param(declare("block_size", ParamType::integer,
                           "leaf block edge of the block tree: 0 (the whole cube as one block, with or without "
                           "workers) or at least " +
                               std::to_string(min_block_size),
                           "cells", 0.0, 4096.0),
                   &O::block_size));
  fields.push_back(choice_param(declare("mode", ParamType::choice,
                                        "tandem-dump (default), tandem (no early dumping), brute (extract, then "
                                        "simplify)",
                                        {}, {}, {}, {"tandem-dump", "tandem", "brute"}),
                                &O::mode));
  fields.push_back(member_param(declare("extended_time_lag", ParamType::boolean,
                                        "delay collapses near open block faces (the seed's section 3.2)"),
                                &O::extended_time_lag));
  // The defaults, read from a default-constructed value. iso has none: a recipe must give it.
  const ExtractionOptions defaults;
  for (auto& f : fields)
    if (f.spec.name != "iso") f.spec.default_value = check_param(f.spec, f.get(defaults), kOwner).text;
  return fields;
}

std::string known_keys() {
  std::string text;
  for (const auto& f : extraction_fields())
    text += (text.empty() ? "" : ", ") + f.spec.name;
  return text;
}

} // namespace

const std::vector<ExtractionField>& extraction_fields() {
  static const std::vector<ExtractionField> fields = make_fields();
  return fields;
}

const std::vector<ParamSpec>& extraction_params() {
  static const std::vector<ParamSpec> specs = [] {
    std::vector<ParamSpec> out;
    for (const auto& f : extraction_fields())
      out.push_back(f.spec);
    return out;
  }();
  return specs;
}

void check_params(const ParamValues& values) {
  const auto block = values.find("block_size");
  if (block == values.end()) return;
  const std::int64_t n = block->second.integer;
  if (n != 0 && n < min_block_size)
    throw InvalidArgument("parameter 'block_size' is " + std::to_string(n) + ", below the smallest block of " +
                              std::to_string(min_block_size) + " cells",
                          {},
                          "use 0 (one block) or at least " + std::to_string(min_block_size) +
                              "; blocks of 64 to 256 cells are typical");
}

void ExtractionOptions::validate() const {
  (void)to_params(*this); // every value against its declaration, then the checks across them
}

ParamValues to_params(const ExtractionOptions& options) {
  ParamValues values;
  for (const auto& f : extraction_fields())
    values[f.spec.name] = check_param(f.spec, f.get(options), kOwner);
  check_params(values);
  return values;
}

ExtractionOptions options_from_params(const ParamValues& values) {
  ExtractionOptions o;
  for (const auto& f : extraction_fields()) {
    const auto at = values.find(f.spec.name);
    if (at == values.end())
      throw InvalidArgument(std::string(kOwner) + ": parameter '" + f.spec.name + "' is not given", {},
                            f.spec.name + ": " + f.spec.help);
    f.set(o, check_param(f.spec, at->second, kOwner));
  }
  check_params(values);
  return o;
}

nlohmann::json to_json(const ExtractionOptions& options) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, v] : to_params(options)) {
    switch (v.type) {
    case ParamType::real: j[name] = v.real; break;
    case ParamType::integer: j[name] = v.integer; break;
    case ParamType::boolean: j[name] = v.boolean; break;
    case ParamType::text:
    case ParamType::choice: j[name] = v.text; break;
    }
  }
  return j;
}

ExtractionOptions options_from_json(const nlohmann::json& json) {
  if (!json.is_object()) throw InvalidArgument(std::string(kOwner) + " are not a JSON object: " + json.dump());
  std::vector<std::string> names;
  for (const auto& f : extraction_fields())
    names.push_back(f.spec.name);
  for (const auto& [key, value] : json.items())
    if (std::find(names.begin(), names.end(), key) == names.end())
      throw InvalidArgument(std::string(kOwner) + ": unknown key '" + key + "'", {},
                            suggestion_hint(key, names) + " (known: " + known_keys() + ")");
  ParamValues values;
  for (const auto& f : extraction_fields()) {
    const std::string& name = f.spec.name;
    if (!json.contains(name)) throw InvalidArgument(std::string(kOwner) + ": '" + name + "' is missing");
    const nlohmann::json& v = json.at(name);
    ParamValue given;
    if (f.spec.type == ParamType::real && v.is_number())
      given = ParamValue(v.get<double>());
    else if (f.spec.type == ParamType::integer && v.is_number_integer())
      given = ParamValue(v.get<std::int64_t>());
    else if (f.spec.type == ParamType::boolean && v.is_boolean())
      given = ParamValue(v.get<bool>());
    else if ((f.spec.type == ParamType::choice || f.spec.type == ParamType::text) && v.is_string())
      given = ParamValue(v.get<std::string>());
    else
      throw InvalidArgument(std::string(kOwner) + ": '" + name + "' is " + v.dump() + ", not " + f.spec.valid_values());
    values[name] = check_param(f.spec, given, kOwner);
  }
  return options_from_params(values);
}

const char* to_string(ExtractMode mode) {
  switch (mode) {
  case ExtractMode::tandem_dump: return "tandem-dump";
  case ExtractMode::tandem: return "tandem";
  case ExtractMode::brute: return "brute";
  }
  return "?";
}

ExtractMode parse_extract_mode(const std::string& text) {
  if (text == "tandem-dump") return ExtractMode::tandem_dump;
  if (text == "tandem") return ExtractMode::tandem;
  if (text == "brute") return ExtractMode::brute;
  throw InvalidArgument("unknown extraction mode '" + text + "'", {}, "use tandem-dump, tandem or brute");
}

const char* to_string(Side side) {
  return side == Side::below ? "below" : "above";
}

Side parse_side(const std::string& text) {
  if (text == "above") return Side::above;
  if (text == "below") return Side::below;
  throw InvalidArgument("unknown side '" + text + "'", {}, "use above (value >= iso) or below (value <= iso)");
}

int parse_axis(const std::string& text) {
  if (text == "i" || text == "0") return 0;
  if (text == "j" || text == "1") return 1;
  if (text == "k" || text == "2") return 2;
  throw InvalidArgument("unknown axis '" + text + "'", {}, "use i (inline), j (crossline) or k (sample)");
}

TandemOptions loop_options(const ExtractionOptions& options) {
  TandemOptions o;
  o.iso = options.iso;
  o.below = options.side == Side::below;
  o.axis = options.axis;
  o.simplify.max_error = options.max_error;
  o.simplify.isotropy = options.isotropy;
  o.simplify.extended_time_lag = options.extended_time_lag;
  o.dump = options.mode != ExtractMode::tandem;
  return o;
}

std::int64_t leaf_size(const ExtractionOptions& options, const volume::Index3& shape) {
  if (options.block_size > 0) return options.block_size;
  std::int64_t cells = 1;
  for (const std::int64_t n : shape)
    cells = std::max(cells, n - 1);
  return cells;
}

} // namespace geotandem::tandem
