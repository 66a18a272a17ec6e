// The workflow's own steps: the extraction, bubble removal, azimuth sorting, exports and the
// report. Each declares its parameters here and nowhere else; the runner reaches them through the
// registry by kind.

#include "geotandem/workflow/builtin_steps.hpp"

#include <filesystem>
#include <sstream>

#include "geotandem/core/error.hpp"
#include "geotandem/core/output_path.hpp"
#include "geotandem/store/export.hpp"
#include "geotandem/workflow/component_steps.hpp"
#include "geotandem/workflow/extract_step.hpp"
#include "geotandem/workflow/report.hpp"
#include "param_builder.hpp"

namespace geotandem::workflow {
namespace {

using detail::param_spec;

// Whether a recipe's output path (relative to the output directory) stays inside it: what a rerun
// may replace. A file elsewhere (an absolute path, or ../ leading out) is never replaced.
bool inside_output_directory(const std::string& path) {
  const auto normal = std::filesystem::path(path).lexically_normal();
  return normal.is_relative() && !normal.empty() && *normal.begin() != "..";
}

// "file format: ply (PLY: ParaView, ...), obj (...), ...": from the export formats' table.
std::string format_help() {
  std::string help;
  for (const auto& f : store::export_formats())
    help += std::string(help.empty() ? "" : "; ") + f.name + " (" + f.summary + ")";
  return "file format: " + help;
}

class BuiltinStep : public Plugin {
public:
  BuiltinStep(std::string name, StepKind kind, std::string summary, std::vector<ParamSpec> params)
      : name_(std::move(name)), kind_(kind), summary_(std::move(summary)), params_(std::move(params)) {}
  const std::string& name() const override { return name_; }
  StepKind kind() const override { return kind_; }
  const std::string& summary() const override { return summary_; }
  const std::vector<ParamSpec>& params() const override { return params_; }
  const std::string& origin() const override { return origin_; }
  const std::string& version() const override { return version_; }

private:
  std::string name_;
  StepKind kind_;
  std::string summary_;
  std::vector<ParamSpec> params_;
  std::string origin_ = "built-in";
  std::string version_ = builtin_version;
};

class ExtractStep final : public BuiltinStep {
public:
  ExtractStep()
      : BuiltinStep("extract", StepKind::extract,
                    "the isosurface by the extended tandem algorithm into the component store", extract_params()) {}
  void check(const ParamValues& values) const override { tandem::check_params(values); }
  ExtractResult extract(const volume::Volume& input, store::ComponentStore& store, const ParamValues& values,
                        const ExecutionContext& execution, StepContext& context) const override {
    return extract_to_store(input, store, tandem::options_from_params(values), execution, context.log, context.progress,
                            context.cancel);
  }
};

class RemoveBubbles final : public BuiltinStep {
public:
  RemoveBubbles()
      : BuiltinStep("remove_bubbles", StepKind::component, "keeps the components above a volume threshold",
                    {param_spec("min_volume", ParamType::real, "0",
                                "keep components of at least this volume, in world units (m^3 or m^2*ms)", 0.0),
                     param_spec("min_volume_fraction", ParamType::real, "0",
                                "keep components of at least this fraction of the largest volume", 0.0, 1.0),
                     param_spec("min_volume_percentile", ParamType::real, "0",
                                "keep components at or above this percentile of volumes", 0.0, 100.0),
                     param_spec("min_triangles", ParamType::integer, "0",
                                "keep components of at least this many triangles", 0.0, 1e12),
                     param_spec("min_samples", ParamType::integer, "0",
                                "keep components enclosing at least this many samples (voxels): the volume "
                                "without units",
                                0.0, 1e15),
                     param_spec("closed_only", ParamType::boolean, "false", "drop components cut by the cube's border"),
                     param_spec("selection", ParamType::text, "kept", "name of the selection this step writes")}) {}
  ComponentOutcome select(store::ComponentStore& store, const ParamValues& p, const std::string& from,
                          StepContext&) const override {
    BubbleRemoval rules;
    rules.min_volume = p.at("min_volume").real;
    rules.min_volume_fraction = p.at("min_volume_fraction").real;
    rules.min_volume_percentile = p.at("min_volume_percentile").real;
    rules.min_triangles = static_cast<std::uint64_t>(p.at("min_triangles").integer);
    rules.min_samples = p.at("min_samples").integer;
    rules.closed_only = p.at("closed_only").boolean;
    rules.from = from;
    rules.selection = p.at("selection").text;
    auto r = remove_bubbles(store, rules);
    std::ostringstream note;
    note << "volume threshold " << r.threshold << " " << volume::volume_unit(store.geometry());
    return {r.before, r.after, rules.selection, note.str(), {{"volume_threshold", r.threshold}}};
  }
};

class SortByAzimuth final : public BuiltinStep {
public:
  SortByAzimuth()
      : BuiltinStep(
            "sort_by_azimuth", StepKind::component,
            "ranks the components by the population of their azimuth bin, the dominant direction first",
            {param_spec("bins", ParamType::integer, "18", "number of azimuth bins over 0-180 degrees", 1.0, 180.0),
             param_spec("azimuth_min", ParamType::real, "0",
                        "keep azimuths from this value (degrees, axial; may wrap past 180)", 0.0, 180.0),
             param_spec("azimuth_max", ParamType::real, "180", "keep azimuths up to this value (degrees)", 0.0, 180.0),
             param_spec("selection", ParamType::text, "sorted", "name of the selection this step writes")}) {}
  ComponentOutcome select(store::ComponentStore& store, const ParamValues& p, const std::string& from,
                          StepContext&) const override {
    AzimuthSorting rules;
    rules.bins = static_cast<int>(p.at("bins").integer);
    rules.azimuth_min = p.at("azimuth_min").real;
    rules.azimuth_max = p.at("azimuth_max").real;
    rules.from = from;
    rules.selection = p.at("selection").text;
    auto r = sort_by_azimuth(store, rules);
    std::ostringstream note;
    note.precision(3);
    note << "mean azimuth " << r.mean_azimuth << " deg, resultant length " << r.resultant_length;
    return {r.before, r.after, rules.selection, note.str(), {{"azimuth_bins", rules.bins}}};
  }
};

class ExportStep final : public BuiltinStep {
public:
  ExportStep()
      : BuiltinStep(
            "export", StepKind::export_step, "writes the components of a selection as surface files",
            {param_spec("format", ParamType::choice, std::nullopt, format_help(), {}, {}, store::export_format_names()),
             param_spec("selection", ParamType::text, "", "the selection to write (empty: the newest one)"),
             param_spec("path", ParamType::text, "",
                        "file (or directory with per_component), relative to the output directory; "
                        "empty: bodies.FORMAT"),
             param_spec("per_component", ParamType::boolean, "false", "one file per component"),
             param_spec("caps", ParamType::boolean, "true",
                        "keep the caps that close bodies cut by the cube's border (false: their open "
                        "surface)")}) {}
  ExportOutcome export_components(const store::ComponentStore& store, const ParamValues& p, const std::string& current,
                                  const std::filesystem::path& out_dir, StepContext& context) const override {
    store::Query q;
    q.selection = p.at("selection").text.empty() ? current : p.at("selection").text;
    auto rows = store.query(q);
    store::ExportOptions options;
    options.format = store::parse_export_format(p.at("format").text);
    options.per_component = p.at("per_component").boolean;
    options.caps = p.at("caps").boolean;
    options.selection = q.selection;
    std::string path = p.at("path").text.empty() ? "bodies." + p.at("format").text : p.at("path").text;
    // A rerun replaces the run's own exports, inside its output directory; a file elsewhere
    // (an absolute path, or ../ leading out) is never replaced.
    options.overwrite = inside_output_directory(path);
    if (rows.empty()) {
      // Nothing to export (no component was extracted, or the component steps kept none): no file,
      // and not the one an earlier run left either, so that the output directory shows this run's
      // result. The run goes on to its report, where the counts say why.
      std::string note = "no " + path + " written";
      std::error_code ec;
      const auto target = out_dir / path;
      const auto status = std::filesystem::symlink_status(target, ec);
      if (options.overwrite && std::filesystem::is_regular_file(status) && std::filesystem::remove(target, ec))
        note += "; the one an earlier run wrote was removed";
      else if (std::filesystem::exists(status))
        note += "; the " + path + " already there is not this run's";
      const std::string from = q.selection.empty() ? "the store" : "the selection '" + q.selection + "'";
      context.log.warning("export " + p.at("format").text + ": " + from + " holds no component: " + note);
      return {0, 0, ""};
    }
    auto summary = store::export_components(store, rows, out_dir / path, options, context.progress, context.cancel);
    return {rows.size(), summary.components, path};
  }
};

class ReportWriter final : public BuiltinStep {
public:
  ReportWriter()
      : BuiltinStep(
            "report", StepKind::report,
            "one self-contained HTML file: the recipe, timings, counts, plots of the components",
            {param_spec("path", ParamType::text, "report.html", "the file, relative to the output directory")}) {}
  std::string write_report(const ReportData& data, const ParamValues& p,
                           const std::filesystem::path& out_dir) const override {
    std::filesystem::path path = out_dir / p.at("path").text;
    // As for the exports: a rerun replaces its own report, never a file outside the output
    // directory, and never a device or a FIFO (writing into one would block or vanish).
    std::error_code ec;
    if (std::filesystem::exists(std::filesystem::symlink_status(path, ec))) {
      if (!inside_output_directory(p.at("path").text))
        throw IoError("the report target already exists outside the output directory", {path.string()},
                      "remove it, or name a new file; a report inside the output directory is replaced by each run");
      require_replaceable(path);
    }
    workflow::write_report(data, path.string());
    return path.string();
  }
};

} // namespace

void register_builtin_steps(PluginRegistry& registry) {
  registry.add(std::make_shared<ExtractStep>());
  registry.add(std::make_shared<RemoveBubbles>());
  registry.add(std::make_shared<SortByAzimuth>());
  registry.add(std::make_shared<ExportStep>());
  registry.add(std::make_shared<ReportWriter>());
}

} // namespace geotandem::workflow
