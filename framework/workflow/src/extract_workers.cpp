// The extraction step through the manager/worker runtime (extract_step.hpp): this process is the
// manager, local worker processes extract, send and merge the blocks.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <thread>

#include "geotandem/core/error.hpp"
#include "geotandem/runtime/bind_address.hpp"
#include "geotandem/runtime/manager.hpp"
#include "geotandem/runtime/scheduler_launcher.hpp"
#include "geotandem/tandem/block_tree.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "geotandem/workflow/extract_step.hpp"

namespace geotandem::workflow {

namespace {

// Seconds from an environment variable (tests shorten the scheduler's intervals), or `fallback`.
std::chrono::milliseconds seconds_from_env(const char* name, std::chrono::milliseconds fallback) {
  const char* text = std::getenv(name);
  if (!text || !*text) return fallback;
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  // At most a billion seconds (32 years): larger values, and inf, would overflow the manager's
  // nanosecond clock and make every task overdue at once.
  if (!(v > 0) || !(v <= 1e9) || (end && *end))
    throw InvalidArgument(std::string(name) + "='" + text + "' is not a number of seconds from 0 to 1e9", {},
                          "unset it or give seconds, e.g. 30");
  return std::chrono::milliseconds(static_cast<long long>(v * 1000));
}

// The workers' launcher: local child processes, or jobs of a cluster scheduler.
std::unique_ptr<runtime::Launcher> make_launcher(const ExtractSettings& settings, const store::ComponentStore& store,
                                                 runtime::ManagerOptions& manager, Logger& log) {
  if (settings.scheduler.empty() || settings.scheduler == "local") return std::make_unique<runtime::LocalLauncher>();
  runtime::SchedulerLaunchOptions o;
  o.backend = settings.scheduler;
  const nlohmann::json& r = settings.resources;
  if (r.is_object()) {
    o.cpus = r.value("cpus_per_worker", 1);
    o.memory_mb = r.value("memory_mb", std::uint64_t{0});
    o.walltime = std::chrono::seconds(r.value("walltime_s", std::int64_t{0}));
    o.queue = r.value("queue", "");
    o.account = r.value("account", "");
    o.extra_args = r.value("extra_args", std::vector<std::string>{});
  }
  const std::filesystem::path logs = std::filesystem::absolute(store.directory()).parent_path() / "worker-logs";
  std::filesystem::create_directories(logs);
  o.workdir = logs.string();
  o.log_pattern = (logs / "{job}.log").string();
  o.poll_interval = seconds_from_env("GEOTANDEM_SCHEDULER_POLL_SECONDS", o.poll_interval);
  o.command_timeout = seconds_from_env("GEOTANDEM_SCHEDULER_COMMAND_TIMEOUT", o.command_timeout);
  // Jobs may wait in the queue: the manager waits longer for the first worker than with local ones.
  manager.connect_timeout = seconds_from_env("GEOTANDEM_SCHEDULER_CONNECT_TIMEOUT", std::chrono::minutes(30));
  log.info("workers run as " + settings.scheduler + " jobs; their logs go to " + logs.string());
  return runtime::make_scheduler_launcher(o, log);
}

// The blocks (leaves) of the tree that blocks of `block_size` cells make of the cube.
std::size_t leaf_count(const volume::Geometry& geometry, std::int64_t block_size) {
  return tandem::BlockTree(tandem::cube_cells(geometry.shape), std::max<std::int64_t>(block_size, 8)).leaves().size();
}

} // namespace

std::size_t default_worker_count(const volume::Geometry& geometry, std::int64_t block_size) {
  if (block_size <= 0) return 0;
  const std::size_t leaves = leaf_count(geometry, block_size);
  if (leaves <= 1) return 0;
  return std::min<std::size_t>(leaves, std::max(1u, std::thread::hardware_concurrency()));
}

ExtractResult extract_with_workers(const volume::Volume& volume, store::ComponentStore& store,
                                   const ExtractSettings& settings, Logger& log, Progress& progress,
                                   const CancelToken& cancel) {
  if (!(store.geometry() == volume.geometry()))
    throw InvalidArgument("the store was made for another cube geometry", {store.directory().string()},
                          "extract into a new store directory");
  if (settings.volume_description.empty() || settings.worker_command.empty())
    throw InvalidArgument("workers need a description of the input volume and a worker command", {},
                          "use --workers 0 to extract in this process");
  if (settings.block_size != 0 && settings.block_size < 8)
    throw InvalidArgument("block size must be at least 8 cells with workers, got " +
                              std::to_string(settings.block_size),
                          {}, "blocks of 64 to 256 cells are typical");
  const auto start = std::chrono::steady_clock::now();
  runtime::ManagerOptions options;
  runtime::RunSettings& r = options.settings;
  r.volume = settings.volume_description;
  r.store = std::filesystem::absolute(store.directory()).string();
  r.block_size = settings.block_size > 0 ? settings.block_size : 64;
  r.iso = settings.iso;
  r.below = settings.below;
  r.axis = settings.axis;
  r.max_error = settings.max_error;
  r.isotropy = settings.isotropy;
  r.extended_time_lag = settings.extended_time_lag;
  r.dump = settings.mode != ExtractMode::tandem;
  r.brute = settings.mode == ExtractMode::brute;
  // One task runs at a time per block: a worker beyond one per block would only start, wait and
  // retire (on a cluster, a job queued for nothing).
  const std::size_t leaves = leaf_count(volume.geometry(), r.block_size);
  options.workers = std::min(settings.workers, leaves);
  if (options.workers < settings.workers)
    log.warning("asked for " + std::to_string(settings.workers) + " workers, but blocks of " +
                std::to_string(r.block_size) + " cells split this cube into " + std::to_string(leaves) +
                (leaves == 1 ? " block" : " blocks") + ": starting " + std::to_string(options.workers) +
                " (smaller blocks give more workers something to do)");
  options.bind = runtime::manager_bind_endpoint(settings.bind);
  options.worker_command = settings.worker_command;
  // The bound after which a task never finished is taken back (manager.hpp).
  options.task_timeout = seconds_from_env("GEOTANDEM_TASK_TIMEOUT_SECONDS", options.task_timeout);
  if (settings.relay_memory_mb >= 0) options.relay_memory = static_cast<std::uint64_t>(settings.relay_memory_mb) << 20;

  ExtractSettings effective = settings;
  effective.block_size = r.block_size;
  nlohmann::json parameters = extract_run_parameters(volume, effective);
  parameters["workers"] = options.workers;

  ExtractResult result;
  result.run = store.begin_run(parameters.dump());
  r.run = result.run;
  std::unique_ptr<runtime::Launcher> launcher = make_launcher(settings, store, options, log);
  runtime::Manager manager(options, store, launcher.get(), log, progress, cancel);
  log.info("extracting with " + std::to_string(options.workers) + " " +
           (settings.scheduler.empty() ? std::string("local") : settings.scheduler) + " worker" +
           (options.workers == 1 ? "" : "s"));
  const std::uint64_t rows_before = store.size();
  const runtime::ManagerReport report = manager.run();
  result.components = report.components;
  result.duplicates = report.duplicates;
  result.repaired = report.repaired;
  result.repaired_keys = report.repaired_keys;
  result.counters = report.counters;
  // Resumed: what the finished blocks hold was in the store already, as what was found again.
  if (report.skipped_leaves > 0) result.duplicates = std::max<std::uint64_t>(result.duplicates, rows_before);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.peak_rss_kb = peak_rss_kb();
  result.blocks = {{"block_size", r.block_size}, {"leaves", report.leaves}, {"merges", report.merge}};
  result.statistics = nlohmann::json::parse(report.to_json());
  result.statistics["peak_rss_kb"] = result.peak_rss_kb;
  if (report.skipped_leaves == 0) warn_if_empty(result, settings, log); // a resumed run may add nothing
  store.end_run(result.run, result.statistics.dump());
  return result;
}

} // namespace geotandem::workflow
