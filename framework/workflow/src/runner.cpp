#include "geotandem/workflow/runner.hpp"

#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <thread>

#include "geotandem/core/atomic_file.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/store/writer_lock.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "geotandem/volume/crs.hpp"
#include "geotandem/volume/fingerprint.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/workflow/chain.hpp"
#include "geotandem/workflow/extract_step.hpp"
#include "geotandem/workflow/label_cube.hpp"
#include "geotandem/workflow/report.hpp"
#include "geotandem/workflow/report_views.hpp"
#include "output_paths.hpp"

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
    // A unique temporary renamed over it, so a kill leaves the old state or the new one, never half
    // of it (AtomicFile).
    write_file_atomically(path_, json_.dump(2) + "\n", "the run state");
  }
  fs::path path_;
  nlohmann::json json_;
};

std::unique_ptr<Progress> progress_of(const WorkflowSettings& settings) {
  return settings.progress ? settings.progress() : std::make_unique<NullProgress>();
}

// The input file's content (size, mtime, sampled checksum) joins the chain's fingerprint,
// so that a cube replaced at the same path is never taken for the one extracted before.
std::string content_suffix(const nlohmann::json& content) {
  if (!content.contains("sampled_checksum")) return "";
  return "+" + content["sampled_checksum"].get<std::string>() + "-" + std::to_string(content.value("size", 0ULL)) +
         "-" + std::to_string(content.value("mtime_ns", 0LL));
}

// What the E0 guarantee held back, for the report: a larger max_error simplifies more.
std::string refused_of(const ExtractResult& r) {
  if (r.counters.rejected_distance == 0) return {};
  return " (" + std::to_string(r.counters.rejected_distance) + " candidates refused by the E0 distance bound)";
}

// The extraction's warnings (no component: an isovalue outside the data?), for the report.
std::string warnings_of(const ExtractResult& r) {
  std::string text;
  for (const auto& w : r.statistics.value("warnings", nlohmann::json::array()))
    text += "; WARNING: " + w.get<std::string>();
  return text;
}

// Test-only, and unset in every real run: with GEOTANDEM_TEST_HOLD_IN_REPORT=PATH the report phase
// creates PATH, then waits there (at most 60 s) until the run is interrupted and carries on, as a
// report that is still being written when Ctrl-C comes does. A test waits for PATH and sends SIGINT,
// so that the signal lands inside the report phase every time (tests/cli/interrupt_cli_test.cpp).
void hold_in_report_for_tests(const CancelToken& cancel) {
  const char* marker = std::getenv("GEOTANDEM_TEST_HOLD_IN_REPORT");
  if (!marker || !*marker) return;
  std::ofstream(marker) << "report phase\n";
  const auto until = Clock::now() + std::chrono::seconds(60);
  while (!cancel.cancelled() && Clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
}

// One run of a validated recipe: walks its steps, then its output steps, calling each through the
// registry by kind. Holds what passes between steps: the store, the newest selection, the report.
class ChainRun {
public:
  ChainRun(const Recipe& recipe, const PluginRegistry& plugins, const WorkflowSettings& settings, Logger& log,
           const CancelToken& cancel, const ChainDescription& chain, const ChainVolumes& volumes)
      : recipe_(recipe), plugins_(plugins), settings_(settings), log_(log), cancel_(cancel), chain_(chain),
        volumes_(volumes), out_dir_(recipe.output.directory), store_dir_(out_dir_ / recipe.output.store),
        state_(out_dir_ / "state.json"), input_content_(volume::input_fingerprint(volumes.input->source())),
        print_(chain.fingerprint() + content_suffix(input_content_)) {
    report_.title = "geotandem run: " + fs::path(recipe.path).stem().string();
    report_.recipe_path = recipe.path;
    report_.recipe = recipe.canonical;
    report_.started = utc_now();
  }

  RunOutcome run() {
    outcome_.output_dir = out_dir_.string();
    outcome_.store_dir = store_dir_.string();
    for (const StepSpec& step : recipe_.steps)
      run_step(step);
    cancel_.throw_if_cancelled();
    write_labels();
    for (const StepSpec& step : recipe_.finish)
      run_step(step);
    remove_input_copy(input_copy_, log_); // kept when the run stops early: a rerun takes it again
    return outcome_;
  }

private:
  // An error that does not say where in the recipe it happened gets the step and its line: a run
  // fails long after the recipe was read, often at one of several steps of the same kind.
  void run_step(const StepSpec& step) {
    // An interrupt between steps stops the run there; each step polls the token inside as well.
    cancel_.throw_if_cancelled();
    try {
      run_step_of_kind(step);
      cancel_.throw_if_cancelled(); // a step that finished after the interrupt does not let the run go on
    } catch (const Cancelled&) {
      throw;
    } catch (const Error& e) {
      if (e.context().line) throw;
      std::string place = "; in the recipe's step '" + step.name + "'";
      if (step.where.line > 0)
        place +=
            " at " + recipe_.path + ":" + std::to_string(step.where.line) + ":" + std::to_string(step.where.column);
      throw_with_note(e, place);
    }
  }

  void run_step_of_kind(const StepSpec& step) {
    const Plugin& plugin = plugins_.get(step.name);
    switch (plugin.kind()) {
    case StepKind::attribute: return; // built lazily in the chain; computed as the extraction reads
    case StepKind::extract: return extract(plugin, step);
    case StepKind::component: return select(plugin, step);
    case StepKind::export_step: return export_components(plugin, step);
    case StepKind::report: return write_report(plugin, step);
    }
    throw InvalidArgument("step '" + step.name + "' has a kind this runner does not know", {recipe_.path});
  }

  StepContext context(Progress& progress) { return StepContext{log_, progress, cancel_}; }

  void extract(const Plugin& plugin, const StepSpec& step) {
    require_cells(volumes_.result->geometry(), volumes_.input->source()); // before anything is written
    if (settings_.fresh && fs::exists(store_dir_)) {
      store::ComponentStore::remove(store_dir_); // Refuses while another process writes it
      log_.info("--fresh: removed the previous store " + store_dir_.string());
      state_.clear();
    }
    if (store::ComponentStore::exists(store_dir_) && state_.fingerprint_of("extract") != print_)
      throw InvalidArgument("the output directory holds a store made with other inputs or parameters",
                            {store_dir_.string()}, "pass --fresh to replace it, or choose another output directory");
    if (!state_.done("extract", print_)) {
      // A file whose chunks reads by blocks decode many times over is copied once, for the
      // attribute file and the extraction (and their workers, through the input hint).
      auto copying = progress_of(settings_);
      const auto t = Clock::now();
      input_copy_ = copy_input_for_blocks(*volumes_.input, (out_dir_ / "input-copy").string(), log_, *copying, cancel_);
      if (!input_copy_.empty())
        report_.steps.push_back({"copy input", since(t), 0, 0, "read by blocks from " + input_copy_});
    }
    write_attribute_file();
    store_.emplace(store::ComponentStore::open_or_create(store_dir_, volumes_.result->geometry(),
                                                         {"geotandem run-workflow", recipe_.path}));
    auto t = Clock::now();
    if (state_.done("extract", print_)) {
      outcome_.extraction_reused = true;
      log_.info("extract: reusing the finished extraction in " + store_dir_.string());
      report_.triangles_per_layer = state_.get("extract").value("triangles_per_layer", std::vector<std::uint64_t>{});
      report_.steps.push_back({step.name, 0.0, 0, store_->size(), "reused from a previous run with the same inputs"});
    } else {
      state_.set("extract", {{"fingerprint", print_}, {"done", false}});
      ExecutionContext run;
      run.record = {{"recipe", recipe_.path},
                    {"chain", chain_.to_json()},
                    {"chain_fingerprint", print_},
                    {"input_content", input_content_}};
      const ExecutionSpec& ex = recipe_.execution;
      // Without `workers`, one per core locally (a cube of one block stays in this process); a
      // cluster scheduler gets the recipe's count.
      const bool cluster = ex.scheduler != "local";
      const std::size_t workers =
          ex.workers_given || cluster || !step.params.count("block_size")
              ? static_cast<std::size_t>(ex.workers)
              : default_worker_count(volumes_.result->geometry(), step.params.at("block_size").integer);
      const bool with_workers = (cluster || workers >= 2) && !settings_.worker_command.empty();
      report_.extract_workers = with_workers ? static_cast<long long>(workers) : 0;
      if (!with_workers && ex.relay_memory_mb >= 0)
        log_.warning("execution.relay_memory is ignored: the extraction runs in this process, so no surface is "
                     "relayed between workers (it applies with execution.workers of 2 or more, or a cluster "
                     "scheduler)");
      if (with_workers) { // the extract step hands the chain to that many workers
        run.workers = workers;
        run.worker_command = settings_.worker_command;
        run.execution = ex;
        nlohmann::json chain = chain_.to_json();
        // What opening the input found (an irregular SEG-Y survey's grid): the workers skip that work.
        if (const std::string hint = volumes_.input->reopen_hint(); !hint.empty()) chain["input"]["reopen_hint"] = hint;
        // The CRS the recipe gives (input.crs, --crs), which the chain's identity leaves out.
        if (recipe_.input.crs) chain["input"]["crs"] = recipe_.input.crs_text;
        run.volume_description = nlohmann::json{{"kind", "chain"}, {"chain", std::move(chain)}}.dump();
        run.record["workers"] = workers;
        run.record["scheduler"] = ex.scheduler;
        run.record["bind"] = ex.bind;
        if (ex.relay_memory_mb >= 0) run.record["relay_memory_mb"] = ex.relay_memory_mb;
      }
      auto progress = progress_of(settings_);
      StepContext c = context(*progress);
      ExtractResult r = plugin.extract(*volumes_.result, *store_, step.params, run, c);
      state_.set("extract", {{"fingerprint", print_},
                             {"done", true},
                             {"run", r.run},
                             {"components", r.components},
                             {"triangles_per_layer", r.triangles_per_layer}});
      report_.triangles_per_layer = r.triangles_per_layer;
      report_.steps.push_back({step.name, since(t), 0, store_->size(),
                               (step.params.count("mode") ? step.params.at("mode").text + ", " : std::string()) +
                                   std::to_string(r.counters.input_triangles) + " marching-cubes triangles, " +
                                   std::to_string(r.counters.collapses) + " collapses" + refused_of(r) +
                                   warnings_of(r)});
    }
    outcome_.components = outcome_.kept = store_->size();
    report_.volume_unit = volume::volume_unit(store_->geometry());
  }

  // Optional: the final attribute cube on disk (an option of the output, not a step).
  void write_attribute_file() {
    if (recipe_.output.attribute_file.empty()) return;
    fs::path path = out_dir_ / recipe_.output.attribute_file;
    if (state_.done("attribute_file", print_) && fs::exists(path)) return;
    auto t = Clock::now();
    auto progress = progress_of(settings_);
    volume::WriteOptions w;
    // Replace only an attribute file this recipe's runs wrote (or with --fresh), never another
    // file (the input cube, say) that happens to sit at that path.
    std::error_code same;
    const bool ours = state_.fingerprint_of("attribute_file") != "" &&
                      state_.get("attribute_file").value("path", "") == path.string();
    w.overwrite = ours || (settings_.fresh && !fs::equivalent(path, volumes_.input->source(), same));
    volume::write_volume(*volumes_.result, path.string(), w, progress.get(), cancel_);
    state_.set("attribute_file", {{"fingerprint", print_}, {"done", true}, {"path", path.string()}});
    report_.steps.push_back({"write attribute", since(t), 0, 0, path.filename().string()});
    report_.outputs.push_back(path.filename().string());
  }

  // Optional: the label cube of the last selection (an option of the output, not a step), from the
  // volume the extraction read, with its iso and side.
  void write_labels() {
    if (recipe_.output.labels_file.empty() || !store_) return;
    refuse_run_file(recipe_.output.labels_file, "labels");
    const fs::path path = out_dir_ / recipe_.output.labels_file;
    const auto t = Clock::now();
    std::vector<std::uint64_t> keys;
    if (!selection_.empty())
      keys = store_->load_selection(selection_).keys;
    else
      for (const auto& row : store_->query())
        keys.push_back(row.key);
    LabelSettings labels;
    for (const StepSpec& step : recipe_.steps)
      if (step.kind == StepKind::extract) {
        labels.iso = static_cast<float>(step.params.at("iso").real);
        labels.below = step.params.count("side") && step.params.at("side").text == "below";
      }
    // Replace only a label cube this recipe's runs wrote (or with --fresh).
    const bool ours = state_.fingerprint_of("labels") != "" && state_.get("labels").value("path", "") == path.string();
    auto progress = progress_of(settings_);
    const nlohmann::json description = {
        {"store", recipe_.output.store},
        {"selection", selection_.empty() ? nlohmann::json(nullptr) : nlohmann::json(selection_)},
        {"recipe", recipe_.path}};
    LabelOutput out = write_label_cube(
        volumes_.result, labels, keys, label_like_of_input(chain_.input), path.string(), ours || settings_.fresh,
        description, "geotandem body labels (0 outside), table in .bodies.csv", progress.get(), cancel_);
    state_.set("labels",
               {{"fingerprint", print_}, {"done", true}, {"path", path.string()}, {"bodies", out.bodies.size()}});
    log_.info("labels: " + std::to_string(out.bodies.size()) + " bodies in " + path.string() + " (table " +
              fs::path(out.table).filename().string() + ")");
    report_.steps.push_back({"write labels", since(t), keys.size(), out.bodies.size(),
                             path.filename().string() + " (" + std::to_string(out.bodies.size()) + " bodies)"});
    report_.outputs.push_back(path.filename().string());
  }

  void select(const Plugin& plugin, const StepSpec& step) {
    auto t = Clock::now();
    auto progress = progress_of(settings_);
    StepContext c = context(*progress);
    ComponentOutcome r = plugin.select(*store_, step.params, selection_, c);
    if (r.figures.count("volume_threshold")) report_.bubble_threshold = r.figures.at("volume_threshold");
    if (r.figures.count("azimuth_bins")) report_.azimuth_bins = static_cast<int>(r.figures.at("azimuth_bins"));
    report_.steps.push_back({step.name, since(t), r.before, r.after, r.note});
    selection_ = r.selection;
    outcome_.kept = r.after;
    cancel_.throw_if_cancelled();
  }

  void export_components(const Plugin& plugin, const StepSpec& step) {
    auto t = Clock::now();
    auto progress = progress_of(settings_);
    StepContext c = context(*progress);
    const std::string path = step.params.at("path").text;
    refuse_run_file(path.empty() ? "bodies." + step.params.at("format").text : path, "");
    ExportOutcome r = plugin.export_components(*store_, step.params, selection_, out_dir_, c);
    const std::string label = step.params.count("format") ? step.name + " " + step.params.at("format").text : step.name;
    report_.steps.push_back({label, since(t), r.rows, r.components, r.path.empty() ? "nothing to export" : r.path});
    if (!r.path.empty()) report_.outputs.push_back(r.path);
  }

  // Checked again as the file is written (validate checked the recipe): a symbolic link made
  // since could lead an output onto one of the run's own files.
  void refuse_run_file(const std::string& path, const std::string& what) const {
    if (auto own =
            detail::run_file_at(recipe_.output, recipe_.input.synthetic, detail::resolved(out_dir_ / path), what))
      throw InvalidArgument("the output " + path + " is " + *own + ": one would overwrite the other", {},
                            "give it another 'path' in the recipe's output section");
  }

  // The report: every component of the store, marked kept when in the final selection.
  void write_report(const Plugin& plugin, const StepSpec& step) {
    refuse_run_file(step.params.at("path").text, "report");
    std::vector<std::uint64_t> kept_keys;
    if (!selection_.empty()) kept_keys = store_->load_selection(selection_).keys;
    std::sort(kept_keys.begin(), kept_keys.end());
    for (const auto& row : store_->query()) {
      ReportComponent c;
      c.key = row.key;
      c.volume = row.stats.volume;
      c.azimuth = row.stats.azimuth;
      c.elongation = row.stats.elongation;
      c.triangles = row.stats.triangle_count;
      c.closed = row.stats.closed;
      c.cut_faces = mesh::cut_faces_text(row.stats.cut_faces);
      if (c.cut_faces.empty() && row.stats.cut_by_border) c.cut_faces = "border";
      c.kept = selection_.empty() || std::binary_search(kept_keys.begin(), kept_keys.end(), row.key);
      report_.components.push_back(c);
    }
    // The map and 3-D views of the kept bodies (report_views.cpp).
    report_.survey = survey_outline(store_->geometry());
    report_.bodies =
        display_bodies(*store_, report_.components, report_.survey, kDisplayTriangleBudget, kDisplayBodies, &cancel_);
    report_.outputs.push_back(recipe_.output.store + "/");
    if (recipe_.input.synthetic) report_.outputs.push_back("truth.json");
    report_.total_seconds = since(report_started_);
    report_.peak_rss_kb = peak_rss_kb();
    hold_in_report_for_tests(cancel_);
    // Interrupted while the views were gathered: no report, and state.json does not say there is one.
    cancel_.throw_if_cancelled();
    outcome_.report = plugin.write_report(report_, step.params, out_dir_);
    state_.set("report", {{"done", true}, {"path", outcome_.report}, {"finished", utc_now()}});
  }

  const Recipe& recipe_;
  const PluginRegistry& plugins_;
  const WorkflowSettings& settings_;
  Logger& log_;
  const CancelToken& cancel_;
  const ChainDescription& chain_;
  const ChainVolumes& volumes_;
  fs::path out_dir_, store_dir_;
  State state_;
  nlohmann::json input_content_; // the input file's content fingerprint
  std::string print_;
  std::string input_copy_; // the input's copy for reads by blocks, when it needed one
  std::optional<store::ComponentStore> store_;
  std::string selection_; // the newest selection: input of the next step and of exports
  ReportData report_;
  RunOutcome outcome_;
  Clock::time_point report_started_ = Clock::now();
};

} // namespace

RunOutcome run_workflow(const Recipe& recipe, const PluginRegistry& plugins, const WorkflowSettings& settings,
                        Logger& log, const CancelToken& cancel) {
  // The input and the attribute chain: lazy volumes, nothing is computed or written until the
  // extraction reads them.
  const ChainDescription chain = describe_chain(recipe, plugins);
  ChainVolumes volumes;
  try {
    auto opening = progress_of(settings); // an irregular SEG-Y survey's pass over its headers
    volumes = open_chain(chain, plugins, opening.get());
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(e.message(), {recipe.path}, e.hint());
  }
  log.info("input: " + volumes.input->source());
  for (const std::string& warning : volume::open_warnings(*volumes.input))
    log.warning(warning);
  if (recipe.input.crs) {
    // The recipe's CRS replaces the file's on the volume the extraction reads (and the store keeps).
    const volume::Crs& file = volumes.input->geometry().crs;
    if (!file.empty() && !(file == *recipe.input.crs))
      log.warning(volumes.input->source() + ": the file says the CRS is " + file.label() + "; input.crs " +
                  recipe.input.crs->label() + " replaces it");
    volumes.result = volume::with_crs(volumes.result, *recipe.input.crs);
  }
  log.info("CRS: " + volumes.result->geometry().crs.label());
  if (settings.dry_run) {
    log.info("dry run: the recipe is valid and its chain builds; the extraction would read " +
             volumes.result->source() + "; nothing was written");
    RunOutcome outcome;
    outcome.output_dir = recipe.output.directory;
    outcome.store_dir = (fs::path(recipe.output.directory) / recipe.output.store).string();
    return outcome;
  }
  if (auto problem = detail::store_problem(recipe.output)) // validate refuses it; a Recipe may be built by hand
    throw InvalidArgument("output.store '" + recipe.output.store + "': " + *problem, {recipe.path},
                          "name a directory inside the output directory, such as 'store'");
  fs::path out_dir = recipe.output.directory;
  fs::create_directories(out_dir);
  // One run per output directory, for the whole run and before anything is written there: a second
  // run would otherwise replace the input's copy, the attribute cube or state.json under the
  // first before its store refused it. The store keeps its own lock (one writer per store).
  const store::DirectoryLock run_lock = store::lock_output_directory(out_dir);
  if (const auto* cube = dynamic_cast<const synth::SyntheticCube*>(volumes.input.get())) {
    synth::write_ground_truth(cube->truth(), (out_dir / "truth.json").string());
    log.info("ground truth of the synthetic cube in " + (out_dir / "truth.json").string());
  }
  ChainRun run(recipe, plugins, settings, log, cancel, chain, volumes);
  return run.run();
}

} // namespace geotandem::workflow
