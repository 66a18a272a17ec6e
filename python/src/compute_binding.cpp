// geotandem._core.extract / run_workflow / synth: the command line's extract, run-workflow and
// synth, called with the same library functions, on a numpy array as well as on a file. Each runs
// through run_cancellable (bridge.hpp): GIL released, progress shown, KeyboardInterrupt honoured.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>

#include "array_volume.hpp"
#include "bindings.hpp"
#include "bridge.hpp"
#include "geotandem/builtin/register.hpp"
#ifdef GEOTANDEM_PYTHON_STEP
#include "geotandem/python_step/register.hpp"
#endif
#include "geotandem/core/error.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "geotandem/volume/crs.hpp"
#include "geotandem/volume/fingerprint.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/workflow/extract_step.hpp"
#include "geotandem/workflow/recipe.hpp"
#include "geotandem/workflow/runner.hpp"

namespace py = pybind11;

namespace geotandem::python {
namespace {

// A Geometry from the dict geotandem.geometry builds (the keys of the raw sidecar's "geometry").
volume::Geometry geometry_of(const py::dict& d) {
  volume::Geometry g;
  auto shape = d["shape"].cast<std::vector<std::int64_t>>();
  if (shape.size() != 3) throw InvalidArgument("a cube has three axes (inline, crossline, sample)");
  g.shape = {shape[0], shape[1], shape[2]};
  g.inline0 = d["inline0"].cast<double>();
  g.inline_step = d["inline_step"].cast<double>();
  g.crossline0 = d["crossline0"].cast<double>();
  g.crossline_step = d["crossline_step"].cast<double>();
  g.z0 = d["z0"].cast<double>();
  g.dz = d["dz"].cast<double>();
  g.z_unit = volume::parse_sample_unit(d["z_unit"].cast<std::string>());
  const py::dict a = d["affine"];
  g.affine = {a["x0"].cast<double>(), a["xi"].cast<double>(), a["xj"].cast<double>(),
              a["y0"].cast<double>(), a["yi"].cast<double>(), a["yj"].cast<double>()};
  g.validate();
  return g;
}

// `g` with `crs` when one is given.
volume::Geometry geometry_with_crs(volume::Geometry g, const std::optional<volume::Crs>& crs) {
  if (crs) g.crs = *crs;
  return g;
}

// The C-contiguous float32 samples of a numpy array of `shape` (geotandem.extract converts).
const float* samples_of(const py::buffer& array, const volume::Geometry& g) {
  py::buffer_info info = array.request();
  // numpy describes an unaligned array (a memmap at an odd offset) with an explicit byte order.
  const bool float32 =
      (info.format == py::format_descriptor<float>::format() || info.format == "<f" || info.format == "=f") &&
      info.itemsize == 4;
  bool contiguous = info.ndim == 3;
  py::ssize_t stride = 4;
  for (py::ssize_t a = 2; contiguous && a >= 0; --a) {
    contiguous = info.strides[static_cast<std::size_t>(a)] == stride &&
                 info.shape[static_cast<std::size_t>(a)] == g.shape[static_cast<std::size_t>(a)];
    stride *= info.shape[static_cast<std::size_t>(a)];
  }
  if (!float32 || !contiguous)
    throw InvalidArgument("the array must be C-contiguous float32 of the geometry's shape", {},
                          "geotandem.extract converts arrays; pass it the array");
  return static_cast<const float*>(info.ptr);
}

// The extraction's declared parameters, for the Python signature and docstring.
py::list extract_param_list() {
  py::list out;
  for (const auto& spec : workflow::extract_params()) {
    py::dict d;
    d["name"] = spec.name;
    d["type"] = to_string(spec.type);
    d["default"] = spec.default_value ? py::object(py::str(*spec.default_value)) : py::object(py::none());
    d["help"] = spec.help;
    d["valid"] = spec.valid_values();
    d["choices"] = spec.choices;
    d["unit"] = spec.unit;
    out.append(d);
  }
  return out;
}

// Values as text (Python formats them), checked by the declarations; errors name the keyword.
workflow::ParamValues extract_values(const std::map<std::string, std::string>& given) {
  workflow::ParamValues values;
  for (const auto& [name, text] : given) {
    const ParamSpec* spec = nullptr;
    for (const auto& s : workflow::extract_params())
      if (s.name == name) spec = &s;
    if (!spec) throw InvalidArgument("extract() got an unexpected parameter '" + name + "'");
    try {
      values[name] = workflow::parse_param(*spec, text);
    } catch (const Error& e) {
      throw InvalidArgument(name + ": " + e.message(), {}, e.hint());
    }
  }
  for (const auto& spec : workflow::extract_params())
    if (!values.count(spec.name)) {
      if (!spec.default_value) throw InvalidArgument("extract() needs the parameter '" + spec.name + "'");
      values[spec.name] = workflow::parse_param(spec, *spec.default_value);
    }
  return values;
}

struct ExtractCall {
  std::string cube_path; // a file, or empty: the array
  const float* samples = nullptr;
  volume::Geometry geometry;
  std::string file; // a read-only memmap's file, read with pread (ArrayVolume)
  std::uint64_t file_offset = 0;
  std::string source;
  std::map<std::string, std::string> params;
  std::string out;
  std::optional<std::size_t> workers;
  bool fresh = false;
  std::string nan = "error";
  std::optional<float> no_data;
  std::string crs; // crs=: an EPSG code or a WKT replacing what the input says; empty: the input's
  std::vector<std::string> worker_command;
};

// cmd_extract.cpp's run, on a file or an array.
py::dict extract_impl(const ExtractCall& c, ReportMode mode, py::object sink) {
  Reporting reporting(mode, std::move(sink));
  CancelToken cancel;
  workflow::ExtractResult r;
  const tandem::ExtractionOptions options = tandem::options_from_params(extract_values(c.params));
  workflow::ExecutionContext s;
  volume::OpenOptions open;
  open.nan_policy = volume::parse_nan_policy(c.nan);
  open.no_data = c.no_data;
  if (!c.crs.empty()) {
    try {
      open.crs = volume::parse_crs(c.crs);
    } catch (const InvalidArgument& e) {
      throw InvalidArgument("crs=: " + e.message(), {}, e.hint());
    }
  }
  const bool below = options.side == tandem::Side::below;
  if (below) open.fill_value = std::numeric_limits<float>::max(); // filled samples stay outside
  run_cancellable(
      [&] {
        std::unique_ptr<volume::Volume> cube;
        if (c.cube_path.empty())
          cube = volume::apply_nan_policy(std::make_unique<ArrayVolume>(geometry_with_crs(c.geometry, open.crs),
                                                                        c.samples, c.source, c.file, c.file_offset),
                                          open);
        else
          cube = volume::open_volume(c.cube_path, open);
        workflow::require_cells(cube->geometry(), c.cube_path.empty() ? c.source : c.cube_path);
        for (const std::string& warning : volume::open_warnings(*cube))
          reporting.log().warning(warning);
        s.workers = c.workers.value_or(
            c.cube_path.empty() ? 0 : workflow::default_worker_count(cube->geometry(), options.block_size));
        if (s.workers > 0) {
          if (c.cube_path.empty())
            throw InvalidArgument("workers need the cube in a file", {},
                                  "geotandem.extract writes the array to a raw file first");
          nlohmann::json d{{"kind", "file"},
                           {"path", std::filesystem::absolute(c.cube_path).string()},
                           {"nan", c.nan},
                           {"variable", ""},
                           {"segy", {{"inline_byte", 189}, {"crossline_byte", 193}}}};
          if (c.no_data) d["no_data"] = *c.no_data;
          if (below) d["fill"] = "highest";
          if (!c.crs.empty()) d["crs"] = c.crs; // the workers' volume says the same CRS
          s.volume_description = d.dump();
          s.worker_command = c.worker_command;
        }
        if (c.fresh) store::ComponentStore::remove(c.out);
        s.record = {{"command", "geotandem.extract (Python)"}, {"cube", c.source.empty() ? c.cube_path : c.source}};
        if (c.no_data) s.record["no_data"] = *c.no_data;
        // An array handed to workers through a copy: the store knows the samples by the array's own
        // identity (its digest, or its memmap's file), as a run in this process does, so that a
        // rerun resumes whatever the copy's name and time, in process or with workers.
        if (!c.cube_path.empty() && !c.source.empty()) s.record["input_content"] = volume::input_fingerprint(c.source);
        auto store =
            store::ComponentStore::open_or_create(c.out, cube->geometry(), {"geotandem.extract", s.record["cube"]});
        auto progress = reporting.progress();
        r = workflow::extract_to_store(*cube, store, options, s, reporting.log(), *progress, cancel);
      },
      cancel, reporting);
  py::dict d;
  d["run"] = r.run, d["components"] = r.components, d["duplicates"] = r.duplicates, d["seconds"] = r.seconds;
  d["peak_rss_kb"] = r.peak_rss_kb, d["workers"] = s.workers, d["statistics"] = r.statistics.dump();
  return d;
}

py::dict extract(py::object array, const std::string& cube_path, const py::dict& geometry, const std::string& crs,
                 const std::string& file, std::uint64_t file_offset, const std::string& source,
                 const std::map<std::string, std::string>& params, const std::string& out,
                 std::optional<std::size_t> workers, bool fresh, const std::string& nan, std::optional<float> no_data,
                 const std::vector<std::string>& worker_command, const std::string& mode, py::object sink) {
  ExtractCall c;
  c.cube_path = cube_path;
  c.crs = crs;
  if (cube_path.empty()) {
    c.geometry = geometry_of(geometry);
    c.samples = samples_of(array, c.geometry); // `array` stays referenced by this frame throughout
  }
  c.file = file, c.file_offset = file_offset, c.source = source, c.params = params, c.out = out, c.workers = workers;
  c.fresh = fresh, c.nan = nan, c.no_data = no_data, c.worker_command = worker_command;
  return extract_impl(c, parse_report_mode(mode), std::move(sink));
}

// Streams an array into a raw cube (PATH + PATH.json), block by block, for worker processes.
void write_raw(const py::buffer& array, const py::dict& geometry, const std::string& file, std::uint64_t file_offset,
               const std::string& path, const std::string& mode, py::object sink) {
  const volume::Geometry g = geometry_of(geometry);
  const float* samples = samples_of(array, g);
  Reporting reporting(parse_report_mode(mode), std::move(sink));
  CancelToken cancel;
  run_cancellable(
      [&] {
        ArrayVolume cube(g, samples, path, file, file_offset);
        volume::WriteOptions options;
        options.overwrite = true;
        auto progress = reporting.progress();
        volume::write_volume(cube, path, options, progress.get(), cancel);
      },
      cancel, reporting);
}

py::dict run_workflow(const std::string& recipe_path, const std::vector<std::string>& overrides, bool fresh,
                      bool dry_run, const std::vector<std::string>& worker_command, const std::string& plugin_path,
                      const std::string& mode, py::object sink) {
  Reporting reporting(parse_report_mode(mode), std::move(sink));
  CancelToken cancel;
  workflow::RunOutcome outcome;
  run_cancellable(
      [&] {
        workflow::PluginRegistry registry;
        builtin::register_builtins(registry);
#ifdef GEOTANDEM_PYTHON_STEP
        python_step::register_python_step(registry); // runs in this interpreter (docs/plugins.md)
#endif
        registry.discover(plugin_path, reporting.log());
        auto recipe = workflow::load_recipe(recipe_path, registry, overrides);
        workflow::WorkflowSettings settings;
        settings.dry_run = dry_run;
        settings.fresh = fresh;
        settings.progress = [&reporting] { return reporting.progress(); };
        settings.worker_command = worker_command;
        outcome = workflow::run_workflow(recipe, registry, settings, reporting.log(), cancel);
      },
      cancel, reporting);
  py::dict d;
  d["output_dir"] = outcome.output_dir, d["store_dir"] = outcome.store_dir, d["report"] = outcome.report;
  d["components"] = outcome.components, d["kept"] = outcome.kept, d["extraction_reused"] = outcome.extraction_reused;
  return d;
}

// geotandem synth: a synthetic cube (and its ground truth, CUBE.truth.json) written to `out`.
void synth(const std::string& out, const std::string& kind, const std::vector<std::int64_t>& shape, std::uint64_t seed,
           bool overwrite, const std::string& mode, py::object sink) {
  if (shape.size() != 3) throw InvalidArgument("shape: three sizes (inline, crossline, sample)");
  Reporting reporting(parse_report_mode(mode), std::move(sink));
  CancelToken cancel;
  run_cancellable(
      [&] {
        std::unique_ptr<synth::SyntheticCube> cube;
        const volume::Index3 size{shape[0], shape[1], shape[2]};
        if (synth::parse_cube_kind(kind) == synth::CubeKind::analytic) {
          synth::AnalyticOptions options;
          options.shape = size, options.seed = seed;
          cube = synth::make_analytic(options);
        } else {
          synth::SeismicOptions options;
          options.shape = size, options.seed = seed;
          cube = synth::make_seismic(options);
        }
        volume::WriteOptions options;
        options.overwrite = overwrite;
        auto progress = reporting.progress();
        volume::write_volume(*cube, out, options, progress.get(), cancel);
        synth::write_ground_truth(cube->truth(), synth::truth_path_for(out));
      },
      cancel, reporting);
}

} // namespace

void bind_compute(py::module_& m) {
  m.def("extract_params", &extract_param_list, "The extract step's declared parameters (name, type, default, ...).");
  m.def("extract", &extract, py::arg("array"), py::arg("cube_path"), py::arg("geometry"), py::arg("crs"),
        py::arg("file"), py::arg("file_offset"), py::arg("source"), py::arg("params"), py::arg("out"),
        py::arg("workers"), py::arg("fresh"), py::arg("nan"), py::arg("no_data"), py::arg("worker_command"),
        py::arg("mode"), py::arg("sink"));
  m.def("write_raw", &write_raw, py::arg("array"), py::arg("geometry"), py::arg("file"), py::arg("file_offset"),
        py::arg("path"), py::arg("mode"), py::arg("sink"));
  m.def(
      "write_raw_sidecar",
      [](const std::string& path, const py::dict& geometry) { volume::write_raw_sidecar(path, geometry_of(geometry)); },
      py::arg("path"), py::arg("geometry"));
  m.def("run_workflow", &run_workflow, py::arg("recipe"), py::arg("overrides"), py::arg("fresh"), py::arg("dry_run"),
        py::arg("worker_command"), py::arg("plugin_path"), py::arg("mode"), py::arg("sink"));
  m.def("synth", &synth, py::arg("out"), py::arg("kind"), py::arg("shape"), py::arg("seed"), py::arg("overwrite"),
        py::arg("mode"), py::arg("sink"));
}

} // namespace geotandem::python
