#include "geotandem/workflow/runner.hpp"

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "geotandem/core/error.hpp"
#include "geotandem/store/export.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/workflow/component_steps.hpp"
#include "geotandem/workflow/extract_step.hpp"
#include "geotandem/workflow/report.hpp"
#include "geotandem/workflow/report_views.hpp"

namespace fs = std::filesystem;

namespace geotandem::workflow {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

std::string utc_now() {
  std::time_t t = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return text;
}

// FNV-1a: a stable 64-bit fingerprint of canonical JSON text (std::hash is not stable).
std::string fingerprint(const nlohmann::json& j) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : j.dump()) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

class State {
public:
  explicit State(fs::path path) : path_(std::move(path)) {
    std::ifstream in(path_);
    if (in) {
      try {
        in >> json_;
      } catch (const nlohmann::json::exception&) {
        json_ = nlohmann::json::object(); // a damaged state only costs recomputation
      }
    }
    if (!json_.is_object()) json_ = nlohmann::json::object();
  }
  bool done(const std::string& step, const std::string& print) const {
    return json_.contains(step) && json_[step].value("fingerprint", "") == print && json_[step].value("done", false);
  }
  std::string fingerprint_of(const std::string& step) const {
    return json_.contains(step) ? json_[step].value("fingerprint", "") : "";
  }
  const nlohmann::json& get(const std::string& step) const { return json_.at(step); }
  void set(const std::string& step, nlohmann::json value) {
    json_[step] = std::move(value);
    save();
  }
  void clear() {
    json_ = nlohmann::json::object();
    save();
  }

private:
  void save() const {
    // Write then rename, so a kill leaves the old state or the new one, never half of it.
    fs::path tmp = path_.string() + ".tmp";
    {
      std::ofstream out(tmp, std::ios::trunc);
      out << json_.dump(2) << '\n';
      if (!out) throw IoError("cannot write the run state", {tmp.string()});
    }
    fs::rename(tmp, path_);
  }
  fs::path path_;
  nlohmann::json json_;
};

std::shared_ptr<const volume::Volume> open_input(const Recipe& r, const fs::path& out_dir, Logger& log) {
  const InputSpec& in = r.input;
  if (in.synthetic) {
    std::unique_ptr<synth::SyntheticCube> cube;
    if (in.synthetic_kind == "analytic") {
      synth::AnalyticOptions o;
      o.shape = {in.shape[0], in.shape[1], in.shape[2]};
      o.seed = in.seed;
      cube = synth::make_analytic(o);
    } else {
      synth::SeismicOptions o;
      o.shape = {in.shape[0], in.shape[1], in.shape[2]};
      o.seed = in.seed;
      o.snr = in.snr;
      cube = synth::make_seismic(o);
    }
    synth::write_ground_truth(cube->truth(), (out_dir / "truth.json").string());
    log.info("input: " + cube->source() + " (ground truth in " + (out_dir / "truth.json").string() + ")");
    return std::shared_ptr<const volume::Volume>(std::move(cube));
  }
  fs::path path = in.file;
  if (path.is_relative() && !r.base_dir.empty()) path = fs::path(r.base_dir) / path;
  volume::OpenOptions options;
  options.nan_policy = volume::parse_nan_policy(in.nan);
  options.variable = in.variable;
  options.segy = {in.segy_inline_byte, in.segy_crossline_byte};
  auto cube = volume::open_volume(path.string(), options);
  log.info("input: " + cube->format() + " " + cube->source());
  return std::shared_ptr<const volume::Volume>(std::move(cube));
}

ExtractSettings extract_settings(const StepSpec& s) {
  ExtractSettings e;
  e.iso = static_cast<float>(s.params.at("iso").real);
  e.max_error = s.params.at("max_error").real;
  e.isotropy = s.params.at("isotropy").real;
  e.axis = parse_axis(s.params.at("axis").text);
  e.block_size = s.params.at("block_size").integer;
  e.mode = parse_extract_mode(s.params.at("mode").text);
  e.extended_time_lag = s.params.at("extended_time_lag").boolean;
  return e;
}

std::unique_ptr<Progress> progress_of(const RunSettings& settings) {
  return settings.progress ? settings.progress() : std::make_unique<NullProgress>();
}

} // namespace

RunOutcome run_workflow(const Recipe& recipe, const PluginRegistry& plugins, const RunSettings& settings, Logger& log,
                        const CancelToken& cancel) {
  auto started = Clock::now();
  RunOutcome outcome;
  fs::path out_dir = recipe.output.directory;
  fs::path store_dir = out_dir / recipe.output.store;
  outcome.output_dir = out_dir.string();
  outcome.store_dir = store_dir.string();

  ReportData report;
  report.title = "geotandem run: " + fs::path(recipe.path).stem().string();
  report.recipe_path = recipe.path;
  report.recipe = recipe.canonical;
  report.started = utc_now();

  if (!settings.dry_run) fs::create_directories(out_dir);
  // The input and the attribute chain: lazy volumes, nothing is computed until extraction reads.
  auto input = settings.dry_run && recipe.input.synthetic ? nullptr : open_input(recipe, out_dir, log);
  if (settings.dry_run && recipe.input.synthetic) {
    // A dry run builds the synthetic cube's description only (cheap) to check the chain.
    input = open_input(recipe, fs::temp_directory_path(), log);
  }
  std::map<std::string, std::shared_ptr<const volume::Volume>> results{{"input", input}};
  std::shared_ptr<const volume::Volume> extract_input;
  const StepSpec* extract = nullptr;
  std::vector<const StepSpec*> component_steps;
  for (const auto& step : recipe.steps) {
    if (step.kind == StepKind::attribute) {
      std::vector<std::shared_ptr<const volume::Volume>> inputs;
      for (const auto& name : step.inputs)
        inputs.push_back(results.at(name));
      try {
        results[step.as] = plugins.get(step.name).make_attribute(std::move(inputs), step.params);
      } catch (const Error& e) {
        throw InvalidArgument(e.message(), {recipe.path, step.where.line, step.where.column}, e.hint());
      }
    } else if (step.kind == StepKind::extract) {
      extract = &step;
      extract_input = results.at(step.inputs.front());
    } else {
      component_steps.push_back(&step);
    }
  }
  if (settings.dry_run) {
    log.info("dry run: the recipe is valid and its chain builds; the extraction would read " + extract_input->source());
    return outcome;
  }

  State state(out_dir / "state.json");
  nlohmann::json extract_identity = {{"input", recipe.canonical["input"]}, {"steps", nlohmann::json::array()}};
  for (const auto& step : recipe.steps) {
    if (step.kind == StepKind::component) break;
    nlohmann::json s = {{"step", step.name}, {"as", step.as}, {"inputs", step.inputs}};
    for (const auto& [k, v] : step.params)
      s["params"][k] = v.text;
    extract_identity["steps"].push_back(s);
  }
  std::string extract_print = fingerprint(extract_identity);

  if (settings.fresh && fs::exists(store_dir)) {
    log.info("--fresh: removing the previous store " + store_dir.string());
    fs::remove_all(store_dir);
    state.clear();
  }
  if (store::ComponentStore::exists(store_dir) && state.fingerprint_of("extract") != extract_print)
    throw InvalidArgument("the output directory holds a store made with other inputs or parameters",
                          {store_dir.string()}, "pass --fresh to replace it, or choose another output directory");

  // Optional: the final attribute cube on disk (an option, not a step).
  if (!recipe.output.attribute_file.empty()) {
    fs::path path = out_dir / recipe.output.attribute_file;
    if (!state.done("attribute_file", extract_print) || !fs::exists(path)) {
      auto t = Clock::now();
      auto progress = progress_of(settings);
      volume::WriteOptions w;
      w.overwrite = true;
      volume::write_volume(*extract_input, path.string(), w, progress.get(), cancel);
      state.set("attribute_file", {{"fingerprint", extract_print}, {"done", true}, {"path", path.string()}});
      report.steps.push_back({"write attribute", since(t), 0, 0, path.filename().string()});
      report.outputs.push_back(path.filename().string());
    }
  }

  auto store = store::ComponentStore::open_or_create(store_dir, extract_input->geometry(),
                                                     {"geotandem run-workflow", recipe.path});
  {
    auto t = Clock::now();
    if (state.done("extract", extract_print)) {
      outcome.extraction_reused = true;
      const auto& s = state.get("extract");
      log.info("extract: reusing the finished extraction in " + store_dir.string());
      report.triangles_per_layer = s.value("triangles_per_layer", std::vector<std::uint64_t>{});
      report.steps.push_back({"extract", 0.0, 0, store.size(), "reused from a previous run with the same inputs"});
    } else {
      state.set("extract", {{"fingerprint", extract_print}, {"done", false}});
      ExtractSettings e = extract_settings(*extract);
      e.parameters = {{"recipe", recipe.path}, {"steps", extract_identity["steps"]}};
      auto progress = progress_of(settings);
      ExtractResult r = extract_to_store(*extract_input, store, e, log, *progress, cancel);
      state.set("extract", {{"fingerprint", extract_print},
                            {"done", true},
                            {"run", r.run},
                            {"components", r.components},
                            {"triangles_per_layer", r.triangles_per_layer}});
      report.triangles_per_layer = r.triangles_per_layer;
      report.steps.push_back({"extract", since(t), 0, store.size(),
                              std::string(to_string(e.mode)) + ", " + std::to_string(r.input_triangles) +
                                  " marching-cubes triangles, " + std::to_string(r.collapses) + " collapses"});
    }
  }
  outcome.components = store.size();
  report.volume_unit = store.geometry().z_unit == volume::SampleUnit::milliseconds ? "m^2*ms" : "m^3";

  std::string selection; // the newest selection, input of the next step and of exports
  for (const StepSpec* step : component_steps) {
    auto t = Clock::now();
    const auto& p = step->params;
    if (step->name == "remove_bubbles") {
      BubbleRemoval rules;
      rules.min_volume = p.at("min_volume").real;
      rules.min_volume_fraction = p.at("min_volume_fraction").real;
      rules.min_volume_percentile = p.at("min_volume_percentile").real;
      rules.min_triangles = static_cast<std::uint64_t>(p.at("min_triangles").integer);
      rules.closed_only = p.at("closed_only").boolean;
      rules.from = selection;
      rules.selection = p.at("selection").text;
      auto r = remove_bubbles(store, rules);
      report.bubble_threshold = r.threshold;
      std::ostringstream note;
      note << "volume threshold " << r.threshold << " " << report.volume_unit;
      report.steps.push_back({"remove_bubbles", since(t), r.before, r.after, note.str()});
      selection = rules.selection;
    } else if (step->name == "sort_by_azimuth") {
      AzimuthSorting rules;
      rules.bins = static_cast<int>(p.at("bins").integer);
      rules.azimuth_min = p.at("azimuth_min").real;
      rules.azimuth_max = p.at("azimuth_max").real;
      rules.from = selection;
      rules.selection = p.at("selection").text;
      auto r = sort_by_azimuth(store, rules);
      report.azimuth_bins = rules.bins;
      std::ostringstream note;
      note.precision(3);
      note << "mean azimuth " << r.mean_azimuth << " deg, resultant length " << r.resultant_length;
      report.steps.push_back({"sort_by_azimuth", since(t), r.before, r.after, note.str()});
      selection = rules.selection;
    }
    cancel.throw_if_cancelled();
  }

  std::vector<std::uint64_t> kept_keys;
  if (!selection.empty()) kept_keys = store.load_selection(selection).keys;
  outcome.kept = selection.empty() ? outcome.components : kept_keys.size();

  for (const auto& e : recipe.output.exports) {
    auto t = Clock::now();
    store::Query q;
    q.selection = e.selection.empty() ? selection : e.selection;
    auto rows = store.query(q);
    store::ExportOptions options;
    options.format = store::parse_export_format(e.format);
    options.per_component = e.per_component;
    auto progress = progress_of(settings);
    auto summary = store::export_components(store, rows, out_dir / e.path, options, *progress, cancel);
    report.steps.push_back({"export " + e.format, since(t), rows.size(), summary.components, e.path});
    report.outputs.push_back(e.path);
  }

  // The report: every component of the store, marked kept when in the final selection.
  std::sort(kept_keys.begin(), kept_keys.end());
  for (const auto& row : store.query()) {
    ReportComponent c;
    c.key = row.key;
    c.volume = row.stats.volume;
    c.azimuth = row.stats.azimuth;
    c.elongation = row.stats.elongation;
    c.triangles = row.stats.triangle_count;
    c.closed = row.stats.closed;
    c.kept = selection.empty() || std::binary_search(kept_keys.begin(), kept_keys.end(), row.key);
    report.components.push_back(c);
  }
  // The map and 3-D views of the kept bodies (report_views.cpp).
  report.survey = survey_outline(store.geometry());
  report.bodies = display_bodies(store, report.components, report.survey);
  report.outputs.push_back(recipe.output.store + "/");
  if (recipe.input.synthetic) report.outputs.push_back("truth.json"); // written by open_input
  report.total_seconds = since(started);
  report.peak_rss_kb = peak_rss_kb();
  fs::path report_path = out_dir / recipe.output.report;
  write_report(report, report_path.string());
  outcome.report = report_path.string();
  state.set("report", {{"done", true}, {"path", report_path.string()}, {"finished", utc_now()}});
  return outcome;
}

} // namespace geotandem::workflow
