// The recipe's sections declared (recipe_schema.hpp), and the tables of docs/recipe-schema.md
// generated from them and from the steps' declarations.
#include "geotandem/workflow/recipe_schema.hpp"

#include <limits>
#include <sstream>
#include <stdexcept>

#include "geotandem/core/error.hpp"
#include "geotandem/core/param_fields.hpp"
#include "geotandem/schedulers/make_scheduler.hpp"
#include "geotandem/synth/options.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/workflow/recipe.hpp"

namespace geotandem::workflow {
namespace {

// A list key of `length` entries (0: any number), each of type `item` within [lo, hi].
ParamSpec list_key(std::string name, std::optional<std::string> default_value, std::string help,
                   ParamType item = ParamType::text, std::size_t length = 0, std::optional<double> lo = {},
                   std::optional<double> hi = {}) {
  ParamSpec s = param_spec(std::move(name), ParamType::text, std::move(default_value), std::move(help), lo, hi);
  s.list = true;
  s.item_type = item;
  s.list_length = length;
  return s;
}

// A text key in a form of its own (a size in MiB, a duration in seconds) of at least `lo`.
ParamSpec form_key(std::string name, ParamSpec::Form form, double lo, std::string help) {
  ParamSpec s = param_spec(std::move(name), ParamType::text, std::nullopt, std::move(help), lo);
  s.form = form;
  return s;
}

// The defaults are the members' initialisers of the specs recipe.hpp fills (and of the libraries'
// option structs they take theirs from): read here, never written again.
std::vector<RecipeSection> make_sections() {
  const InputSpec in;
  const OutputSpec out;
  const ExecutionSpec ex;
  const ResourceSpec res;
  const volume::SegyOptions segy;
  std::vector<RecipeSection> s;

  RecipeSection input{"input", {}, {}, {"segy", "synthetic"}};
  input.keys = {
      param_spec(
          "file", ParamType::text, std::nullopt,
          "the cube: SEG-Y, netCDF-4, Zarr, HDF5, GeoTIFF/ENVI, or raw float32 with its JSON sidecar. The format is "
          "found from the file itself. A relative path is relative to the recipe's directory. Exactly one of `file` "
          "or `synthetic`"),
      param_spec(
          "no_data", ParamType::real, std::nullopt,
          "samples of this value are missing too, as NaN samples are (`nan` decides): the null of a SEG-Y or raw "
          "cube, which cannot declare one (-999.25 is common). A netCDF, Zarr, GeoTIFF or ENVI file's own no-data "
          "value is honoured without it. A file input only",
          -static_cast<double>(std::numeric_limits<float>::max()),
          static_cast<double>(std::numeric_limits<float>::max())),
      param_spec(
          "variable", ParamType::text, std::nullopt,
          "the array to read from a netCDF, Zarr or HDF5 file holding several cubes (a name such as `chaos` or a "
          "full name such as `/group/chaos`); without it such a file is refused with the list of its arrays"),
      param_spec(
          "nan", ParamType::choice, in.nan,
          "missing samples (NaN, infinite, or equal to the no-data value the file declares: docs/formats-gdal.md): "
          "stop with an error naming the file, the box and the first bad sample, or fill them. Filled, they are "
          "never inside a body: read directly by `extract`, they are the lowest float; under attributes, the "
          "attributes see them as dead samples (0, as the dead traces that pad an irregular survey) and the "
          "attribute is the lowest float wherever the input is missing",
          {}, {}, {"error", "fill"}),
      param_spec(
          "crs", ParamType::text, std::nullopt,
          "the coordinate reference system of the map coordinates: an EPSG code (`EPSG:23031`) or a WKT, checked "
          "through GDAL's OSR while the recipe is read (an unknown code, or a geographic CRS in degrees, is refused "
          "at its line and column). It replaces the CRS the file says (a netCDF CF `grid_mapping`, a `crs` "
          "attribute, a GeoTIFF/ENVI georeference) and is kept in the store, its runs and every export; without "
          "either, outputs say \"no CRS given\". `--crs` on `run-workflow` sets it. It changes no component: a "
          "store keeps its keys and its extraction with or without it"),
  };
  input.keys[1].single_precision = true;
  input.absent = {{"file", "—"}, {"no_data", "—"}, {"variable", "the only 3-D array"}, {"crs", "the file's"}};
  s.push_back(input);

  RecipeSection segy_section{"input.segy", {}, {}, {}};
  const std::vector<std::string> header_types{"int16", "int32", "ieee", "float", "ibm"};
  const auto type_key = [&](const std::string& name, volume::HeaderType value, const std::string& what) {
    return param_spec(name, ParamType::choice, std::string(volume::to_string(value)),
                      "SEG-Y only: the type (and so the width: int16 2 bytes, the others 4) of the " + what +
                          " field; `float` is `ieee`",
                      {}, {}, header_types);
  };
  segy_section.keys = {
      param_spec("inline_byte", ParamType::integer, std::to_string(segy.inline_byte),
                 "SEG-Y only: the trace header byte (1-based) holding the inline number; 9, 5, 17 and 221 are common "
                 "(docs/formats-segy-raw.md). The field must end by byte 240. `geotandem info` names the positions "
                 "that work when these do not",
                 1, 239),
      param_spec("crossline_byte", ParamType::integer, std::to_string(segy.crossline_byte),
                 "SEG-Y only: the trace header byte (1-based) holding the crossline number; 21, 13 and 225 are common",
                 1, 239),
      type_key("inline_type", segy.inline_type, "inline number"),
      type_key("crossline_type", segy.crossline_type, "crossline number"),
      param_spec("x_byte", ParamType::integer, std::to_string(segy.x_byte),
                 "SEG-Y only: the trace header byte (1-based) of the CDP X coordinate", 1, 239),
      param_spec("y_byte", ParamType::integer, std::to_string(segy.y_byte),
                 "SEG-Y only: the trace header byte (1-based) of the CDP Y coordinate", 1, 239),
      type_key("x_type", segy.x_type, "CDP X"),
      type_key("y_type", segy.y_type, "CDP Y"),
      param_spec("coordinate_scalar", ParamType::integer, std::nullopt,
                 "SEG-Y only: the coordinate scalar of every trace instead of the header's (bytes 71-72): negative "
                 "divides, positive multiplies, 0 means 1",
                 -32768, 32767),
  };
  segy_section.absent = {{"coordinate_scalar", "bytes 71-72 of each trace"}};
  s.push_back(segy_section);

  RecipeSection synthetic{"input.synthetic", {}, {}, {}};
  synthetic.keys = {
      param_spec("kind", ParamType::choice, in.synthetic_kind, "a synthetic cube with ground truth (docs/synthetic.md)",
                 {}, {}, {"seismic", "analytic"}),
      list_key("shape",
               "[" + std::to_string(in.shape[0]) + ", " + std::to_string(in.shape[1]) + ", " +
                   std::to_string(in.shape[2]) + "]",
               "[NI, NJ, NK]: inline, crossline, sample counts (the planted bodies need room)", ParamType::integer, 3,
               synth::min_edge, 100000),
      param_spec("seed", ParamType::integer, std::to_string(in.seed), "same seed, same cube, bit for bit", 0,
                 static_cast<double>(std::int64_t{1} << 40)),
      param_spec("snr", ParamType::real, number_text(in.snr), "signal-to-noise ratio of the seismic kind", 1e-3, 1e6),
  };
  s.push_back(synthetic);

  RecipeSection output{"output", {}, {}, {}};
  output.keys = {
      param_spec("directory", ParamType::text, std::nullopt,
                 "where everything goes; a relative path is relative to the working directory you run from"),
      param_spec("store", ParamType::text, out.store,
                 "the component store, inside `directory` (not `.`, the directory itself, nor a directory holding it)"),
      param_spec(
          "report", ParamType::text, out.report,
          "the HTML report, relative to `directory`; each run replaces its own report there, but an existing file "
          "outside `directory` (an absolute path, or `../`), a device or a FIFO is never replaced (exit 3, after the "
          "store and exports are written), as for exports"),
      param_spec(
          "attribute", ParamType::text, std::nullopt,
          "also write the final attribute cube there (format from the extension: .nc, .zarr, .raw); an existing file "
          "there is replaced only when a previous run of the recipe wrote it (or with `--fresh`, never the input "
          "cube)"),
      param_spec("labels", ParamType::text, std::nullopt,
                 "also write the label cube there, after the component steps (docs/label-cube.md): each sample's body "
                 "ID (0 outside every kept body of the last selection) on the input's grid, in the input's format "
                 "family (a SEG-Y input: SEG-Y with its trace headers; netCDF, Zarr: the same with its coordinates; "
                 "raw: raw with its sidecar; the extension must say that family), with a table of IDs to store keys "
                 "beside it (PATH.bodies.csv, PATH.bodies.json). Replaced only when a previous run of the recipe wrote "
                 "it (or with `--fresh`)"),
      list_key("exports", std::nullopt,
               "a list of exports, each with the parameters of the `export` step (below): selection defaults to the "
               "last one written (a named one must be written by a component step of the recipe), path to "
               "`bodies.FORMAT` (two exports may not share a file, however named; an export may not be one of the "
               "run's own files, `report.html`, `state.json`, `truth.json`, the attribute cube or anything in the "
               "store: `validate` refuses it at its line). An export whose selection holds no component writes no "
               "file, removes the one an earlier run wrote in the output directory, and warns"),
  };
  output.keys.back().table_items = true;
  output.absent = {
      {"directory", "`<recipe name>-out`"}, {"attribute", "none"}, {"labels", "none"}, {"exports", "none"}};
  s.push_back(output);

  std::string backends;
  for (const auto& b : schedulers::scheduler_backends())
    backends += (backends.empty() ? "" : "; ") + ("`" + b.name + "`: " + b.summary);
  RecipeSection execution{"execution", {}, {}, {"resources"}};
  execution.keys = {
      param_spec("scheduler", ParamType::choice, ex.scheduler, "where workers run (`--scheduler`): " + backends, {}, {},
                 schedulers::scheduler_names()),
      param_spec("workers", ParamType::integer, std::nullopt, "worker count", 1, 4096),
      form_key("relay_memory", ParamSpec::Form::size_mib, 0,
               "partial surfaces the manager holds in memory while they wait for their merge; "
               "past it they wait on disk beside the store (docs/runtime.md). Only with workers: an extraction in one "
               "process warns that it ignores it"),
      param_spec("bind", ParamType::text, std::nullopt,
                 "an interface, IPv4 address[:port] or `loopback`: where the manager listens (`--bind`); anything but "
                 "loopback turns CurveZMQ on; a wildcard (0.0.0.0) or an unknown interface is refused at validation"),
  };
  execution.absent = {{"workers", "`local`: one per core, at most one per block (a cube of one block: in this "
                                  "process); `slurm`, `lsf`: 1"},
                      {"relay_memory", "`1G`"},
                      {"bind", "loopback"}};
  s.push_back(execution);

  RecipeSection resources{"execution.resources", {}, {}, {}};
  resources.keys = {
      param_spec("cpus_per_worker", ParamType::integer, std::to_string(res.cpus_per_worker),
                 "cores asked for each worker", 1, 1024),
      form_key("memory", ParamSpec::Form::size_mib, 1, "memory asked for each worker"),
      form_key("walltime", ParamSpec::Form::duration_s, 1, "each worker's time limit"),
      param_spec("queue", ParamType::text, std::nullopt, "Slurm partition or LSF queue"),
      param_spec("account", ParamType::text, std::nullopt, "the account jobs are charged to"),
      list_key("extra_args", std::nullopt, "a list of words passed to sbatch / bsub verbatim"),
  };
  resources.absent = {{"memory", "scheduler default"},
                      {"walltime", "scheduler default"},
                      {"queue", "—"},
                      {"account", "—"},
                      {"extra_args", "—"}};
  s.push_back(resources);
  return s;
}

std::string code(const std::string& text) {
  return "`" + text + "`";
}

std::string type_text(const ParamSpec& p) {
  std::string t;
  switch (p.type) {
  case ParamType::choice:
    for (const auto& c : p.choices)
      t += (t.empty() ? "" : " \\| ") + code(c);
    return t;
  case ParamType::text:
    if (p.list) {
      const ParamSpec e = p.entry();
      const std::string count = p.list_length ? std::to_string(p.list_length) + " " : std::string();
      if (p.table_items) return "list of " + count + "tables";
      if (e.type == ParamType::text) return "list of " + count + "words";
      return "list of " + (p.list_length ? std::to_string(p.list_length) + ", each " : std::string("")) + type_text(e);
    }
    switch (p.form) {
    case ParamSpec::Form::size_mib: return "size (`2048M`, `4G`; MiB without a unit)";
    case ParamSpec::Form::duration_s: return "duration (`hh:mm:ss`, `hh:mm`, minutes)";
    case ParamSpec::Form::plain: break;
    }
    return "text";
  case ParamType::boolean: return "boolean";
  case ParamType::integer: t = p.odd ? "odd integer" : "integer"; break;
  case ParamType::real: t = "real"; break;
  }
  if (p.min_value || p.max_value) t += " " + p.range_text();
  if (!p.unit.empty()) t += ", " + p.unit;
  return t;
}

} // namespace

std::vector<std::string> RecipeSection::key_names() const {
  std::vector<std::string> names;
  for (const auto& k : keys)
    names.push_back(k.name);
  for (const auto& nested : sections)
    names.push_back(nested);
  return names;
}

const std::vector<RecipeSection>& recipe_sections() {
  static const std::vector<RecipeSection> sections = make_sections();
  return sections;
}

const RecipeSection& recipe_section(std::string_view path) {
  for (const auto& s : recipe_sections())
    if (s.path == path) return s;
  throw std::out_of_range("no recipe section '" + std::string(path) + "' is declared");
}

std::string params_table(const std::vector<ParamSpec>& keys, const std::map<std::string, std::string>& absent) {
  std::ostringstream t;
  t << "| key | type | default | meaning |\n| --- | --- | --- | --- |\n";
  for (const auto& p : keys) {
    std::string def;
    if (p.default_value)
      def = p.default_value->empty() ? "`\"\"`" : code(*p.default_value);
    else if (auto at = absent.find(p.name); at != absent.end())
      def = at->second;
    else
      def = "required";
    t << "| " << code(p.name) << " | " << type_text(p) << " | " << def << " | " << p.help << " |\n";
  }
  return t.str();
}

std::string regenerate_schema_doc(const std::string& document, const PluginRegistry& registry) {
  static const std::string open = "<!-- generated: ", close = "<!-- end generated -->";
  std::istringstream in(document);
  std::ostringstream out;
  std::string line;
  while (std::getline(in, line)) {
    out << line << "\n";
    if (line.rfind(open, 0) != 0) continue;
    const std::string what = line.substr(open.size(), line.find(" -->") - open.size());
    bool closed = false;
    while (std::getline(in, line))
      if (line == close) {
        closed = true;
        break;
      }
    if (!closed) throw InvalidArgument("the generated table '" + what + "' has no '" + close + "' line");
    if (what.rfind("step ", 0) == 0) {
      const Plugin& step = registry.get(what.substr(5));
      out << params_table(step.params());
    } else {
      try {
        const RecipeSection& section = recipe_section(what);
        out << params_table(section.keys, section.absent);
      } catch (const std::out_of_range&) {
        throw InvalidArgument("no recipe section '" + what + "' is declared", {},
                              "use a section's path (input, input.synthetic, execution.resources, ...) or 'step NAME'");
      }
    }
    out << close << "\n";
  }
  return out.str();
}

} // namespace geotandem::workflow
