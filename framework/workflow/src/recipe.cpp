#include "geotandem/workflow/recipe.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>

#include "geotandem/core/error.hpp"
#include "geotandem/synth/options.hpp"
#include "geotandem/volume/crs.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/volume/size_guard.hpp"
#include "geotandem/workflow/label_cube.hpp"
#include "geotandem/workflow/suggest.hpp"
#include "output_paths.hpp"
#include "recipe_execution.hpp"
#include "recipe_overrides.hpp"
#include "yaml_reader.hpp"

namespace fs = std::filesystem;

namespace geotandem::workflow {
namespace {

using detail::error_at;
using detail::MapReader;
using detail::parse_execution;
using detail::RecipeSource;

// The input section, read through its declaration (recipe_schema.cpp); what the declaration cannot
// say alone (file or synthetic, a shape of three sizes that fits this machine) is checked here.
void parse_input(MapReader& m, InputSpec& in) {
  in.where = m.source().where_of(m.map());
  bool has_file = m.has("file"), has_synth = m.has("synthetic");
  if (has_file == has_synth)
    throw error_at(m.source(), m.map(), "input needs exactly one of 'file' or 'synthetic'",
                   "file: path/to/cube.segy, or synthetic: {kind: seismic, shape: [160, 160, 128]}");
  const RecipeSection& section = recipe_section("input");
  const ParamValues given = detail::read_section(m, section);
  in.nan = given.at("nan").text;
  if (m.has("no_data") && has_synth)
    throw error_at(m.source(), m.node("no_data"), "'no_data' applies to a file input",
                   "a synthetic cube has no missing samples");
  if (given.count("no_data")) in.no_data = given.at("no_data").real; // a float sample's value
  if (given.count("variable")) in.variable = given.at("variable").text;
  if (given.count("crs")) {
    // Declared as text; what the declaration cannot check (a CRS OSR knows) is checked here.
    in.crs_text = given.at("crs").text;
    try {
      in.crs = volume::parse_crs(in.crs_text);
    } catch (const Error& e) {
      throw error_at(m.source(), m.node("crs"), "input.crs: " + e.message(), e.hint());
    }
  }
  if (m.has("segy")) {
    const RecipeSection& segy = recipe_section("input.segy");
    MapReader s(m.source(), m.node("segy"), segy.path);
    const ParamValues b = detail::read_section(s, segy);
    volume::SegyOptions& o = in.segy;
    o.inline_byte = static_cast<int>(b.at("inline_byte").integer);
    o.crossline_byte = static_cast<int>(b.at("crossline_byte").integer);
    o.x_byte = static_cast<int>(b.at("x_byte").integer);
    o.y_byte = static_cast<int>(b.at("y_byte").integer);
    o.inline_type = volume::parse_header_type(b.at("inline_type").text);
    o.crossline_type = volume::parse_header_type(b.at("crossline_type").text);
    o.x_type = volume::parse_header_type(b.at("x_type").text);
    o.y_type = volume::parse_header_type(b.at("y_type").text);
    if (b.count("coordinate_scalar")) o.coordinate_scalar = static_cast<int>(b.at("coordinate_scalar").integer);
    try {
      volume::check_segy_options(o);
    } catch (const Error& e) {
      throw error_at(m.source(), m.node("segy"), e.message(), e.hint());
    }
    s.finish(segy.key_names());
  }
  if (has_file) {
    in.file = m.required_text("file");
  } else {
    in.synthetic = true;
    const RecipeSection& synthetic = recipe_section("input.synthetic");
    MapReader s(m.source(), m.node("synthetic"), synthetic.path);
    const ParamValues p = detail::read_section(s, synthetic);
    in.synthetic_kind = p.at("kind").text;
    if (s.has("shape")) {
      const std::vector<ParamValue> shape = detail::read_list(s, find_param(synthetic.keys, "shape"), synthetic.path);
      for (int a = 0; a < 3; ++a)
        in.shape[a] = shape[static_cast<std::size_t>(a)].integer;
      // A shape this machine cannot hold is refused here, with the numbers, not at run time.
      try {
        volume::check_shape_fits({in.shape[0], in.shape[1], in.shape[2]}, "input.synthetic.shape");
      } catch (const InvalidArgument& e) {
        throw error_at(m.source(), s.node("shape"), e.message(), e.hint());
      }
    }
    in.seed = static_cast<std::uint64_t>(p.at("seed").integer);
    in.snr = p.at("snr").real;
    s.finish(synthetic.key_names());
  }
  m.finish(section.key_names());
}

// A list parameter's text ("[1, 1, 8]") from a YAML list of scalars (ParamSpec::list).
std::string list_text(MapReader& m, const YAML::Node& list, const std::string& what) {
  std::string text = "[";
  for (std::size_t n = 0; n < list.size(); ++n)
    text += (n ? ", " : "") + detail::scalar_of(m.source(), list[n], "an entry of " + what);
  return text + "]";
}

// `base_dir`: the recipe's directory, against which recipe_path parameters are made absolute.
ParamValues parse_params(MapReader& m, const std::vector<ParamSpec>& specs, const std::string& what,
                         const std::string& base_dir = {}) {
  ParamValues values;
  for (const auto& spec : specs) {
    std::string text;
    // YAML::Node's operator= assigns content through the reference: rebind with reset().
    YAML::Node at;
    at.reset(m.map());
    if (m.has(spec.name)) {
      at.reset(m.node(spec.name));
      if (spec.list && at.IsSequence())
        text = list_text(m, at, "'" + spec.name + "' in " + what);
      else
        text = m.scalar(spec.name);
    } else if (spec.default_value) {
      text = *spec.default_value;
    } else {
      std::vector<std::string> names;
      for (const auto& s : specs)
        names.push_back(s.name);
      m.missing(spec.name, names, spec.name + ": " + spec.help + " (" + to_string(spec.type) + ")");
    }
    if (spec.recipe_path && !text.empty()) {
      fs::path path = fs::absolute(fs::path(base_dir) / text).lexically_normal();
      if (path.filename().empty() && path.has_relative_path()) path = path.parent_path(); // "dir/" -> "dir"
      text = path.string();
    }
    try {
      values[spec.name] = parse_param(spec, text);
    } catch (const Error& e) {
      throw error_at(m.source(), at, what + ": " + e.message(), e.hint());
    }
  }
  return values;
}

// Runs the step's own checks (beyond each parameter's spec). The error is placed at the parameter
// it names ("parameter 'block_size' ...") when the recipe gives it, else at the step.
void check_step(MapReader& m, const Plugin& plugin, const ParamValues& values, const std::string& what) {
  try {
    plugin.check(values);
  } catch (const Error& e) {
    YAML::Node at;
    at.reset(m.map());
    for (const auto& spec : plugin.params())
      if (e.message().find("'" + spec.name + "'") != std::string::npos && m.has(spec.name)) {
        at.reset(m.node(spec.name));
        break;
      }
    throw error_at(m.source(), at, what + ": " + e.message(), e.hint());
  }
}

StepSpec parse_step(const RecipeSource& source, const YAML::Node& node, std::size_t index,
                    const PluginRegistry& plugins) {
  MapReader m(source, node, "step " + std::to_string(index + 1));
  StepSpec step;
  step.where = source.where_of(node);
  if (!m.has("step"))
    throw error_at(source, node, "step " + std::to_string(index + 1) + " needs 'step: NAME'",
                   "NAME is a step listed by 'geotandem plugins' (an attribute, extract, remove_bubbles, ...)");
  step.name = m.required_text("step");
  std::string what = "step " + std::to_string(index + 1) + " (" + step.name + ")";
  const Plugin* plugin = plugins.find(step.name);
  if (!plugin) {
    std::string hint;
    try {
      plugins.get(step.name);
    } catch (const Error& e) {
      hint = e.hint();
    }
    throw error_at(source, m.node("step"), "unknown step or plugin '" + step.name + "'", hint);
  }
  step.kind = plugin->kind();
  if (step.kind == StepKind::export_step || step.kind == StepKind::report)
    throw error_at(source, m.node("step"),
                   what + " is " + (step.kind == StepKind::export_step ? "an export" : "the report") +
                       ", which belongs in the output section, not in the steps",
                   step.kind == StepKind::export_step ? "output: {exports: [{format: vtp}]}"
                                                      : "output: {report: FILE}");
  m.rename(what);
  const std::vector<ParamSpec>& specs = plugin->params();
  step.arity = plugin->input_count();
  step.as = m.text("as", step.name);
  if (m.has("input") && m.has("inputs"))
    throw error_at(source, node, what + " has both 'input' and 'inputs'", "use one of them");
  step.inputs = m.has("inputs") ? m.text_list("inputs") : m.text_list("input");
  step.params = parse_params(m, specs, what, fs::path(source.file()).parent_path().string());
  std::vector<std::string> known = {"step", "as", "input", "inputs"};
  for (const auto& s : specs)
    known.push_back(s.name);
  m.finish(known);
  check_step(m, *plugin, step.params, what);
  return step;
}

// Checks the chain: names resolve to earlier results, arity, one extraction after the volume
// steps, component steps after it.
void check_chain(const RecipeSource& source, const YAML::Node& steps_node, std::vector<StepSpec>& steps) {
  std::set<std::string> results = {"input"};
  std::string previous = "input";
  bool extracted = false;
  for (std::size_t n = 0; n < steps.size(); ++n) {
    StepSpec& s = steps[n];
    const YAML::Node at = steps_node[n];
    std::string what = "step " + std::to_string(n + 1) + " (" + s.name + ")";
    if (s.kind == StepKind::component) {
      if (!extracted)
        throw error_at(source, at, what + " works on components, but no extract step comes before it",
                       "put an extract step first");
      if (!s.inputs.empty()) throw error_at(source, at, what + " takes no input: it works on the store");
      continue;
    }
    if (extracted)
      throw error_at(source, at, what + " comes after the extract step", "volume steps must come before extract");
    if (s.inputs.empty()) s.inputs = {previous};
    for (const auto& in : s.inputs)
      if (!results.count(in))
        throw error_at(source, at, what + " reads '" + in + "', which no earlier step produces",
                       suggestion_hint(in, std::vector<std::string>(results.begin(), results.end())));
    if (s.inputs.size() != static_cast<std::size_t>(s.arity))
      throw error_at(source, at,
                     what + " takes " + std::to_string(s.arity) + " input(s), got " + std::to_string(s.inputs.size()),
                     s.arity > 1 ? "inputs: [a, b]" : "input: NAME, or nothing for the previous step's result");
    if (s.kind == StepKind::extract) {
      extracted = true;
      continue;
    }
    if (results.count(s.as) && s.as != "input")
      throw error_at(source, at, what + " is named '" + s.as + "', like an earlier result", "give it another 'as:'");
    results.insert(s.as);
    previous = s.as;
  }
  if (!extracted)
    throw error_at(source, steps_node, "the steps have no extract step", "add '- step: extract' with 'iso:'");
}

// The step of `kind` named `name` in the registry, or an error saying the registry lacks it.
const Plugin& output_step(const PluginRegistry& plugins, const std::string& name, StepKind kind) {
  const Plugin* step = plugins.find(name);
  if (!step || step->kind() != kind)
    throw InvalidArgument(std::string("no ") + to_string(kind) + " step '" + name + "' is registered", {},
                          "register the built-in steps (workflow::register_builtin_steps)");
  return *step;
}

// The output section: where results go, and the export and report steps it asks for.
void parse_output(MapReader& m, Recipe& r, const std::string& recipe_stem, const PluginRegistry& plugins) {
  OutputSpec& out = r.output;
  std::vector<std::string> selections;  // written by the component steps
  std::vector<YAML::Node> export_nodes; // where each export is, for check_output_paths
  for (const auto& step : r.steps)
    if (step.kind == StepKind::component && step.params.count("selection"))
      selections.push_back(step.params.at("selection").text);
  const RecipeSection& section = recipe_section("output");
  const ParamValues v = detail::read_section(m, section);
  out.directory = v.count("directory") ? v.at("directory").text : recipe_stem + "-out";
  out.store = v.at("store").text;
  out.attribute_file = v.count("attribute") ? v.at("attribute").text : "";
  if (!out.attribute_file.empty()) {
    try {
      volume::check_output_format(out.attribute_file);
    } catch (const InvalidArgument& e) {
      throw error_at(m.source(), m.node("attribute"), "output.attribute: " + e.message(), e.hint());
    }
  }
  out.labels_file = v.count("labels") ? v.at("labels").text : "";
  if (!out.labels_file.empty()) {
    // In the input's format family (label_cube.hpp), known here when the input file is there.
    LabelLike like;
    std::error_code ec;
    const fs::path input = fs::path(r.base_dir) / r.input.file;
    if (!r.input.synthetic && !r.input.file.empty() && fs::exists(input, ec)) like.file = input.string();
    try {
      check_label_format(like, out.labels_file);
    } catch (const InvalidArgument& e) {
      throw error_at(m.source(), m.node("labels"), "output.labels: " + e.message(), e.hint());
    } catch (const Error&) { // an input that cannot be read is reported as the input's error
    }
  }
  // A synthetic input's shape is known now: an attribute cube the disk cannot hold is refused here.
  if (!out.attribute_file.empty() && r.input.synthetic) {
    try {
      volume::check_disk_fits({r.input.shape[0], r.input.shape[1], r.input.shape[2]},
                              std::filesystem::path(out.directory) / out.attribute_file, "output.attribute");
    } catch (const IoError& e) {
      throw error_at(m.source(), m.node("attribute"), e.message(), e.hint());
    }
  }
  if (m.has("exports")) {
    const Plugin& exporter = output_step(plugins, "export", StepKind::export_step);
    YAML::Node list = m.node("exports");
    if (!list.IsSequence()) throw error_at(m.source(), list, "'exports' must be a list");
    for (std::size_t n = 0; n < list.size(); ++n) {
      std::string what = "export " + std::to_string(n + 1);
      MapReader e(m.source(), list[n], what);
      StepSpec step;
      step.kind = StepKind::export_step;
      step.name = step.as = exporter.name();
      step.where = m.source().where_of(list[n]);
      step.params = parse_params(e, exporter.params(), what);
      std::vector<std::string> known;
      for (const auto& s : exporter.params())
        known.push_back(s.name);
      e.finish(known);
      check_step(e, exporter, step.params, what);
      const std::string& wanted = step.params.at("selection").text;
      if (!wanted.empty() && std::find(selections.begin(), selections.end(), wanted) == selections.end())
        throw error_at(m.source(), e.node("selection"),
                       what + " exports selection '" + wanted + "', which no component step of the recipe writes",
                       selections.empty() ? std::string("leave 'selection' out to export every component")
                                          : suggestion_hint(wanted, selections));
      ExportSpec spec;
      spec.format = step.params.at("format").text;
      spec.selection = step.params.at("selection").text;
      spec.path = step.params.at("path").text.empty() ? "bodies." + spec.format : step.params.at("path").text;
      spec.per_component = step.params.at("per_component").boolean;
      spec.caps = step.params.at("caps").boolean;
      out.exports.push_back(spec);
      export_nodes.push_back(list[n]);
      r.finish.push_back(std::move(step));
    }
  }
  const Plugin& reporter = output_step(plugins, "report", StepKind::report);
  StepSpec report;
  report.kind = StepKind::report;
  report.name = report.as = reporter.name();
  report.where = m.source().where_of(m.map());
  report.params = default_values(reporter.params());
  if (m.has("report")) {
    YAML::Node at = m.node("report");
    std::string text = detail::scalar_of(m.source(), at, "'report' in output");
    try {
      report.params["path"] = parse_param(reporter.params().front(), text);
    } catch (const Error& e) {
      throw error_at(m.source(), at, e.message() + " in output", e.hint());
    }
  }
  out.report = report.params.at("path").text;
  r.finish.push_back(std::move(report));
  detail::check_output_paths(m, r, export_nodes);
  m.finish(section.key_names());
}

nlohmann::json to_json(const Recipe& r) {
  using nlohmann::json;
  json j;
  json in;
  if (r.input.synthetic)
    in["synthetic"] = {{"kind", r.input.synthetic_kind},
                       {"shape", {r.input.shape[0], r.input.shape[1], r.input.shape[2]}},
                       {"seed", r.input.seed},
                       {"snr", r.input.snr}};
  else
    in["file"] = r.input.file;
  in["nan"] = r.input.nan;
  if (r.input.no_data) in["no_data"] = *r.input.no_data;
  if (!r.input.variable.empty()) in["variable"] = r.input.variable;
  if (r.input.crs) in["crs"] = r.input.crs_text; // left out of the chain's description (describe_chain)
  if (!(r.input.segy == volume::SegyOptions{})) in["segy"] = volume::to_json(r.input.segy);
  j["input"] = in;
  j["steps"] = json::array();
  for (const auto& s : r.steps) {
    json step = {{"step", s.name}, {"as", s.as}, {"inputs", s.inputs}};
    for (const auto& [k, v] : s.params)
      step["params"][k] = v.text;
    j["steps"].push_back(step);
  }
  j["output"] = {{"directory", r.output.directory}, {"store", r.output.store}, {"report", r.output.report}};
  if (!r.output.labels_file.empty()) j["output"]["labels"] = r.output.labels_file;
  for (const auto& e : r.output.exports)
    j["output"]["exports"].push_back({{"format", e.format},
                                      {"selection", e.selection},
                                      {"path", e.path},
                                      {"per_component", e.per_component},
                                      {"caps", e.caps}});
  j["execution"] = {{"scheduler", r.execution.scheduler}, {"workers", r.execution.workers}};
  return j;
}

} // namespace

Recipe parse_recipe(const std::string& text, const std::string& name, const PluginRegistry& plugins,
                    const std::vector<std::string>& overrides) {
  // One document, no duplicate keys, no control characters (yaml_reader.cpp).
  YAML::Node root = detail::load_single_document(text, name);
  RecipeSource source(name);
  for (const auto& o : overrides) {
    const detail::GraftedOverride grafted = detail::apply_override(root, o);
    source.add_override(grafted.key, grafted.value, o);
  }

  Recipe r;
  r.path = name;
  r.base_dir = fs::path(name).parent_path().string();
  MapReader top(source, root, "the recipe");
  std::int64_t version = top.integer("version", 1, 1, 1);
  (void)version;
  if (!top.has("input")) throw error_at(source, root, "the recipe has no 'input' section");
  if (!top.has("steps")) throw error_at(source, root, "the recipe has no 'steps' section");
  MapReader input(source, top.node("input"), "input");
  parse_input(input, r.input);
  YAML::Node steps = top.node("steps");
  if (!steps.IsSequence() || steps.size() == 0)
    throw error_at(source, steps, "'steps' must be a non-empty list of steps");
  for (std::size_t n = 0; n < steps.size(); ++n)
    r.steps.push_back(parse_step(source, steps[n], n, plugins));
  check_chain(source, steps, r.steps);
  std::string stem = fs::path(name).stem().string();
  {
    YAML::Node empty(YAML::NodeType::Map);
    MapReader out(source, top.has("output") ? top.node("output") : empty, "output");
    parse_output(out, r, stem, plugins);
  }
  if (top.has("execution")) {
    MapReader ex(source, top.node("execution"), "execution");
    parse_execution(ex, r.execution);
  }
  top.finish({"version", "input", "steps", "output", "execution"});
  r.canonical = to_json(r);
  return r;
}

Recipe load_recipe(const std::string& path, const PluginRegistry& plugins, const std::vector<std::string>& overrides) {
  // Regular files only (a FIFO or /dev/zero would block or never end), with a size limit.
  std::string text = detail::read_recipe_text(path);
  return parse_recipe(text, path, plugins, overrides);
}

} // namespace geotandem::workflow
