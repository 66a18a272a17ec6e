#include "geotandem/workflow/recipe.hpp"

#include <filesystem>
#include <fstream>
#include <set>

#include "geotandem/core/error.hpp"
#include "geotandem/workflow/suggest.hpp"
#include "yaml_reader.hpp"

namespace fs = std::filesystem;

namespace geotandem::workflow {
namespace {

using detail::error_at;
using detail::MapReader;

constexpr std::int64_t big = std::int64_t(1) << 40;

StepKind kind_of(const std::string& name) {
  if (name == "extract") return StepKind::extract;
  if (name == "remove_bubbles" || name == "sort_by_azimuth") return StepKind::component;
  return StepKind::attribute;
}

void parse_input(MapReader& m, InputSpec& in) {
  in.where = detail::where_of(m.map());
  bool has_file = m.has("file"), has_synth = m.has("synthetic");
  if (has_file == has_synth)
    throw error_at(m.file(), m.map(), "input needs exactly one of 'file' or 'synthetic'",
                   "file: path/to/cube.segy, or synthetic: {kind: seismic, shape: [160, 160, 128]}");
  in.nan = m.text("nan", "error");
  if (in.nan != "error" && in.nan != "fill")
    throw error_at(m.file(), m.node("nan"), "'nan' is '" + in.nan + "'", "use 'error' or 'fill'");
  in.variable = m.text("variable", "");
  if (m.has("segy")) {
    MapReader s(m.file(), m.node("segy"), "input.segy");
    in.segy_inline_byte = static_cast<int>(s.integer("inline_byte", 189, 1, 240));
    in.segy_crossline_byte = static_cast<int>(s.integer("crossline_byte", 193, 1, 240));
    s.finish({"inline_byte", "crossline_byte"});
  }
  if (has_file) {
    in.file = m.required_text("file");
  } else {
    in.synthetic = true;
    MapReader s(m.file(), m.node("synthetic"), "input.synthetic");
    in.synthetic_kind = s.text("kind", "seismic");
    if (in.synthetic_kind != "seismic" && in.synthetic_kind != "analytic")
      throw error_at(m.file(), s.node("kind"), "synthetic kind '" + in.synthetic_kind + "' is unknown",
                     suggestion_hint(in.synthetic_kind, {"seismic", "analytic"}));
    if (s.has("shape")) {
      YAML::Node shape = s.node("shape");
      if (!shape.IsSequence() || shape.size() != 3)
        throw error_at(m.file(), shape, "shape must be a list of three sizes [inline, crossline, sample]");
      for (int a = 0; a < 3; ++a) {
        std::string t = detail::scalar_of(m.file(), shape[a], "a shape entry");
        char* end = nullptr;
        long long v = std::strtoll(t.c_str(), &end, 10);
        if (t.empty() || *end != '\0' || v < 16 || v > 100000)
          throw error_at(m.file(), shape[a], "shape entry '" + t + "' must be an integer from 16 to 100000");
        in.shape[a] = v;
      }
    }
    in.seed = static_cast<std::uint64_t>(s.integer("seed", 1, 0, big));
    in.snr = s.real("snr", 4.0, 1e-3, 1e6);
    s.finish({"kind", "shape", "seed", "snr"});
  }
  m.finish({"file", "synthetic", "nan", "variable", "segy"});
}

ParamValues parse_params(MapReader& m, const std::vector<ParamSpec>& specs, const std::string& what) {
  ParamValues values;
  for (const auto& spec : specs) {
    std::string text;
    // YAML::Node's operator= assigns content through the reference: rebind with reset().
    YAML::Node at;
    at.reset(m.map());
    if (m.has(spec.name)) {
      at.reset(m.node(spec.name));
      text = detail::scalar_of(m.file(), at, "'" + spec.name + "' in " + what);
    } else if (spec.default_value) {
      text = *spec.default_value;
    } else {
      throw error_at(m.file(), m.map(), what + " needs '" + spec.name + "'",
                     spec.name + ": " + spec.help + " (" + to_string(spec.type) + ")");
    }
    try {
      values[spec.name] = parse_param(spec, text);
    } catch (const Error& e) {
      throw error_at(m.file(), at, e.message() + " in " + what, e.hint());
    }
  }
  return values;
}

StepSpec parse_step(const std::string& file, const YAML::Node& node, std::size_t index, const PluginRegistry& plugins) {
  MapReader m(file, node, "step " + std::to_string(index + 1));
  StepSpec step;
  step.where = detail::where_of(node);
  if (!m.has("step"))
    throw error_at(file, node, "step " + std::to_string(index + 1) + " needs 'step: NAME'",
                   "NAME is an attribute (see 'geotandem plugins') or extract, remove_bubbles, sort_by_azimuth");
  step.name = m.required_text("step");
  step.kind = kind_of(step.name);
  std::string what = "step " + std::to_string(index + 1) + " (" + step.name + ")";
  m.rename(what);
  const std::vector<ParamSpec>* specs = nullptr;
  if (step.kind == StepKind::attribute) {
    const Plugin* plugin = plugins.find(step.name);
    if (!plugin) {
      std::vector<std::string> names = builtin_step_names();
      for (const Plugin* p : plugins.list())
        names.push_back(p->name());
      std::string hint = suggestion_hint(step.name, names);
      try {
        plugins.get(step.name);
      } catch (const Error& e) {
        hint = e.hint();
        for (const auto& n : builtin_step_names())
          if (nearest(step.name, {n}) == n) hint = "did you mean '" + n + "'?";
      }
      throw error_at(file, m.node("step"), "unknown step or plugin '" + step.name + "'", hint);
    }
    specs = &plugin->params();
    step.arity = plugin->input_count();
  } else {
    specs = &builtin_step_params(step.name);
  }
  step.as = m.text("as", step.name);
  if (m.has("input") && m.has("inputs"))
    throw error_at(file, node, what + " has both 'input' and 'inputs'", "use one of them");
  step.inputs = m.has("inputs") ? m.text_list("inputs") : m.text_list("input");
  step.params = parse_params(m, *specs, what);
  std::vector<std::string> known = {"step", "as", "input", "inputs"};
  for (const auto& s : *specs)
    known.push_back(s.name);
  m.finish(known);
  return step;
}

// Checks the chain: names resolve to earlier results, arity, one extraction after the volume
// steps, component steps after it.
void check_chain(const std::string& file, const YAML::Node& steps_node, std::vector<StepSpec>& steps) {
  std::set<std::string> results = {"input"};
  std::string previous = "input";
  bool extracted = false;
  for (std::size_t n = 0; n < steps.size(); ++n) {
    StepSpec& s = steps[n];
    const YAML::Node at = steps_node[n];
    std::string what = "step " + std::to_string(n + 1) + " (" + s.name + ")";
    if (s.kind == StepKind::component) {
      if (!extracted)
        throw error_at(file, at, what + " works on components, but no extract step comes before it",
                       "put an extract step first");
      if (!s.inputs.empty()) throw error_at(file, at, what + " takes no input: it works on the store");
      continue;
    }
    if (extracted)
      throw error_at(file, at, what + " comes after the extract step", "volume steps must come before extract");
    if (s.inputs.empty()) s.inputs = {previous};
    for (const auto& in : s.inputs)
      if (!results.count(in))
        throw error_at(file, at, what + " reads '" + in + "', which no earlier step produces",
                       suggestion_hint(in, std::vector<std::string>(results.begin(), results.end())));
    if (s.inputs.size() != static_cast<std::size_t>(s.arity))
      throw error_at(file, at,
                     what + " takes " + std::to_string(s.arity) + " input(s), got " + std::to_string(s.inputs.size()),
                     s.arity > 1 ? "inputs: [a, b]" : "input: NAME, or nothing for the previous step's result");
    if (s.kind == StepKind::extract) {
      extracted = true;
      continue;
    }
    if (results.count(s.as) && s.as != "input")
      throw error_at(file, at, what + " is named '" + s.as + "', like an earlier result", "give it another 'as:'");
    results.insert(s.as);
    previous = s.as;
  }
  if (!extracted)
    throw error_at(file, steps_node, "the steps have no extract step", "add '- step: extract' with 'iso:'");
}

void parse_output(MapReader& m, OutputSpec& out, const std::string& recipe_stem) {
  out.directory = m.text("directory", recipe_stem + "-out");
  out.store = m.text("store", "store");
  out.report = m.text("report", "report.html");
  out.attribute_file = m.text("attribute", "");
  if (m.has("exports")) {
    YAML::Node list = m.node("exports");
    if (!list.IsSequence()) throw error_at(m.file(), list, "'exports' must be a list");
    for (const auto& item : list) {
      MapReader e(m.file(), item, "an export");
      ExportSpec spec;
      spec.format = e.required_text("format");
      if (spec.format != "ply" && spec.format != "obj" && spec.format != "vtp" && spec.format != "ts")
        throw error_at(m.file(), e.node("format"), "unknown export format '" + spec.format + "'",
                       suggestion_hint(spec.format, {"ply", "obj", "vtp", "ts"}));
      spec.selection = e.text("selection", "");
      spec.path = e.text("path", "bodies." + spec.format);
      spec.per_component = e.boolean("per_component", false);
      e.finish({"format", "selection", "path", "per_component"});
      out.exports.push_back(spec);
    }
  }
  m.finish({"directory", "store", "report", "attribute", "exports"});
}

std::int64_t parse_walltime(const std::string& file, const YAML::Node& node, const std::string& text) {
  // [[hh:]mm:]ss or a plain number of minutes
  int h = 0, mi = 0, s = 0;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%d:%d:%d%c", &h, &mi, &s, &extra) == 3) return h * 3600 + mi * 60 + s;
  if (std::sscanf(text.c_str(), "%d:%d%c", &h, &mi, &extra) == 2) return h * 3600 + mi * 60;
  if (std::sscanf(text.c_str(), "%d%c", &mi, &extra) == 1 && mi > 0) return mi * 60;
  throw error_at(file, node, "walltime '" + text + "' is not hh:mm:ss, hh:mm or minutes");
}

std::int64_t parse_memory(const std::string& file, const YAML::Node& node, const std::string& text) {
  char* end = nullptr;
  double v = std::strtod(text.c_str(), &end);
  std::string unit = end ? end : "";
  double mb = unit == "" || unit == "M" || unit == "MB" ? v : unit == "G" || unit == "GB" ? v * 1024 : -1;
  if (!(v > 0) || mb < 0) throw error_at(file, node, "memory '" + text + "' is not a size like 2048M or 4G");
  return static_cast<std::int64_t>(mb);
}

void parse_execution(MapReader& m, ExecutionSpec& ex) {
  ex.scheduler = m.text("scheduler", "local");
  if (ex.scheduler != "local" && ex.scheduler != "slurm" && ex.scheduler != "lsf")
    throw error_at(m.file(), m.node("scheduler"), "unknown scheduler '" + ex.scheduler + "'",
                   suggestion_hint(ex.scheduler, {"local", "slurm", "lsf"}));
  ex.workers = static_cast<int>(m.integer("workers", 1, 1, 4096));
  if (m.has("resources")) {
    MapReader r(m.file(), m.node("resources"), "execution.resources");
    ex.resources.cpus_per_worker = static_cast<int>(r.integer("cpus_per_worker", 1, 1, 1024));
    if (r.has("memory")) {
      YAML::Node n = r.node("memory");
      ex.resources.memory_mb = parse_memory(m.file(), n, detail::scalar_of(m.file(), n, "memory"));
    }
    if (r.has("walltime")) {
      YAML::Node n = r.node("walltime");
      ex.resources.walltime_s = parse_walltime(m.file(), n, detail::scalar_of(m.file(), n, "walltime"));
    }
    ex.resources.queue = r.text("queue", "");
    ex.resources.account = r.text("account", "");
    ex.resources.extra_args = r.text_list("extra_args");
    r.finish({"cpus_per_worker", "memory", "walltime", "queue", "account", "extra_args"});
  }
  m.finish({"scheduler", "workers", "resources"});
}

// Applies one --set override to the YAML tree. Steps are addressed by index (steps.2.iso) or by
// their 'as' / step name (steps.extract.iso).
void apply_override(YAML::Node root, const std::string& text) {
  auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InvalidArgument("--set '" + text + "' is not key=value", {}, "for example --set execution.workers=4");
  std::string path = text.substr(0, eq), value = text.substr(eq + 1);
  std::vector<std::string> parts;
  for (std::size_t start = 0;;) {
    auto dot = path.find('.', start);
    parts.push_back(path.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  YAML::Node node;
  node.reset(root);
  for (std::size_t n = 0; n + 1 < parts.size(); ++n) {
    const std::string& part = parts[n];
    if (node.IsSequence()) {
      YAML::Node found;
      bool matched = false; // a default YAML::Node is a valid null node, so track the match apart
      char* end = nullptr;
      long index = std::strtol(part.c_str(), &end, 10);
      if (*end == '\0' && index >= 1 && static_cast<std::size_t>(index) <= node.size()) {
        found.reset(node[static_cast<std::size_t>(index - 1)]);
        matched = true;
      } else {
        for (std::size_t i = 0; i < node.size() && !matched; ++i) {
          YAML::Node item = node[i];
          if (item.IsMap() && ((item["as"] && item["as"].Scalar() == part) ||
                               (!item["as"] && item["step"] && item["step"].Scalar() == part))) {
            found.reset(item);
            matched = true;
          }
        }
      }
      if (!matched)
        throw InvalidArgument("--set " + text + ": no step '" + part + "'", {},
                              "address steps by their 1-based index or by name");
      node.reset(found);
    } else {
      if (!node[part]) node[part] = YAML::Node(YAML::NodeType::Map);
      node.reset(node[part]);
    }
  }
  node[parts.back()] = YAML::Load(value);
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
  if (!r.input.variable.empty()) in["variable"] = r.input.variable;
  if (r.input.segy_inline_byte != 189 || r.input.segy_crossline_byte != 193)
    in["segy"] = {{"inline_byte", r.input.segy_inline_byte}, {"crossline_byte", r.input.segy_crossline_byte}};
  j["input"] = in;
  j["steps"] = json::array();
  for (const auto& s : r.steps) {
    json step = {{"step", s.name}, {"as", s.as}, {"inputs", s.inputs}};
    for (const auto& [k, v] : s.params)
      step["params"][k] = v.text;
    j["steps"].push_back(step);
  }
  j["output"] = {{"directory", r.output.directory}, {"store", r.output.store}, {"report", r.output.report}};
  for (const auto& e : r.output.exports)
    j["output"]["exports"].push_back(
        {{"format", e.format}, {"selection", e.selection}, {"path", e.path}, {"per_component", e.per_component}});
  j["execution"] = {{"scheduler", r.execution.scheduler}, {"workers", r.execution.workers}};
  return j;
}

} // namespace

Recipe parse_recipe(const std::string& text, const std::string& name, const PluginRegistry& plugins,
                    const std::vector<std::string>& overrides) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InvalidArgument("not valid YAML: " + e.msg, {name, e.mark.line + 1, e.mark.column + 1},
                          "check indentation and the ':' after each key");
  }
  for (const auto& o : overrides)
    apply_override(root, o);

  Recipe r;
  r.path = name;
  r.base_dir = fs::path(name).parent_path().string();
  MapReader top(name, root, "the recipe");
  std::int64_t version = top.integer("version", 1, 1, 1);
  (void)version;
  if (!top.has("input")) throw error_at(name, root, "the recipe has no 'input' section");
  if (!top.has("steps")) throw error_at(name, root, "the recipe has no 'steps' section");
  MapReader input(name, top.node("input"), "input");
  parse_input(input, r.input);
  YAML::Node steps = top.node("steps");
  if (!steps.IsSequence() || steps.size() == 0)
    throw error_at(name, steps, "'steps' must be a non-empty list of steps");
  for (std::size_t n = 0; n < steps.size(); ++n)
    r.steps.push_back(parse_step(name, steps[n], n, plugins));
  check_chain(name, steps, r.steps);
  std::string stem = fs::path(name).stem().string();
  if (top.has("output")) {
    MapReader out(name, top.node("output"), "output");
    parse_output(out, r.output, stem);
  } else {
    r.output.directory = stem + "-out";
  }
  if (top.has("execution")) {
    MapReader ex(name, top.node("execution"), "execution");
    parse_execution(ex, r.execution);
  }
  top.finish({"version", "input", "steps", "output", "execution"});
  r.canonical = to_json(r);
  return r;
}

Recipe load_recipe(const std::string& path, const PluginRegistry& plugins, const std::vector<std::string>& overrides) {
  std::ifstream in(path);
  if (!in) throw IoError("cannot read the recipe", {path}, "check the path");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parse_recipe(text, path, plugins, overrides);
}

} // namespace geotandem::workflow
