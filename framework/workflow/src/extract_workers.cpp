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
std::unique_ptr<runtime::Launcher> make_launcher(const ExecutionSpec& execution, const store::ComponentStore& store,
                                                 runtime::ManagerOptions& manager, Logger& log) {
  if (execution.scheduler.empty() || execution.scheduler == "local") return std::make_unique<runtime::LocalLauncher>();
  runtime::SchedulerLaunchOptions o;
  o.backend = execution.scheduler;
  const ResourceSpec& r = execution.resources;
  o.cpus = r.cpus_per_worker;
  o.memory_mb = static_cast<std::uint64_t>(r.memory_mb);
  o.walltime = std::chrono::seconds(r.walltime_s);
  o.queue = r.queue;
  o.account = r.account;
  o.extra_args = r.extra_args;
  const std::filesystem::path logs = std::filesystem::absolute(store.directory()).parent_path() / "worker-logs";
  std::filesystem::create_directories(logs);
  o.workdir = logs.string();
  o.log_pattern = (logs / "{job}.log").string();
  o.poll_interval = seconds_from_env("GEOTANDEM_SCHEDULER_POLL_SECONDS", o.poll_interval);
  o.command_timeout = seconds_from_env("GEOTANDEM_SCHEDULER_COMMAND_TIMEOUT", o.command_timeout);
  // Jobs may wait in the queue: the manager waits longer for the first worker than with local ones.
  manager.connect_timeout = seconds_from_env("GEOTANDEM_SCHEDULER_CONNECT_TIMEOUT", std::chrono::minutes(30));
  log.info("workers run as " + execution.scheduler + " jobs; their logs go to " + logs.string());
  return runtime::make_scheduler_launcher(o, log);
}

// The blocks (leaves) of the tree the manager builds for these options (block_size 0: one).
std::size_t leaf_count(const volume::Geometry& geometry, const ExtractionOptions& options) {
  return tandem::BlockTree(tandem::cube_cells(geometry.shape), tandem::leaf_size(options, geometry.shape))
      .leaves()
      .size();
}

} // namespace

std::size_t default_worker_count(const volume::Geometry& geometry, std::int64_t block_size) {
  if (block_size <= 0) return 0;
  ExtractionOptions options;
  options.block_size = block_size;
  const std::size_t leaves = leaf_count(geometry, options);
  if (leaves <= 1) return 0;
  return std::min<std::size_t>(leaves, std::max(1u, std::thread::hardware_concurrency()));
}

ExtractResult extract_with_workers(const volume::Volume& volume, store::ComponentStore& store,
                                   const ExtractionOptions& extraction, const ExecutionContext& context, Logger& log,
                                   Progress& progress, const CancelToken& cancel) {
  if (!store.geometry().same_grid(volume.geometry()))
    throw InvalidArgument("the store was made for another cube geometry", {store.directory().string()},
                          "extract into a new store directory");
  if (context.volume_description.empty() || context.worker_command.empty())
    throw InvalidArgument("workers need a description of the input volume and a worker command", {},
                          "use --workers 0 to extract in this process");
  extraction.validate();
  const auto start = std::chrono::steady_clock::now();
  runtime::ManagerOptions options;
  runtime::RunSettings& r = options.settings;
  r.volume = context.volume_description;
  r.store = std::filesystem::absolute(store.directory()).string();
  r.extraction = extraction; // unchanged: the manager and every worker read the same value
  const ExecutionSpec& ex = context.execution;
  // One task runs at a time per block: a worker beyond one per block would only start, wait and
  // retire (on a cluster, a job queued for nothing).
  const std::size_t leaves = leaf_count(volume.geometry(), extraction);
  options.workers = std::min(context.workers, leaves);
  if (options.workers < context.workers)
    log.warning("asked for " + std::to_string(context.workers) + " workers, but " +
                (extraction.block_size > 0
                     ? "blocks of " + std::to_string(extraction.block_size) + " cells split this cube into " +
                           std::to_string(leaves) + (leaves == 1 ? " block" : " blocks")
                     : std::string("block_size 0 makes the whole cube one block")) +
                ": starting " + std::to_string(options.workers) +
                " (smaller blocks give more workers something to do)");
  options.bind = runtime::manager_bind_endpoint(ex.bind);
  options.worker_command = context.worker_command;
  // The bound after which a task never finished is taken back (manager.hpp).
  options.task_timeout = seconds_from_env("GEOTANDEM_TASK_TIMEOUT_SECONDS", options.task_timeout);
  if (ex.relay_memory_mb >= 0) options.relay_memory = static_cast<std::uint64_t>(ex.relay_memory_mb) << 20;

  nlohmann::json parameters = extract_run_parameters(volume, extraction, context);
  parameters["workers"] = options.workers;

  ExtractResult result;
  result.run = store.begin_run(parameters.dump());
  r.run = result.run;
  std::unique_ptr<runtime::Launcher> launcher = make_launcher(ex, store, options, log);
  runtime::Manager manager(options, store, launcher.get(), log, progress, cancel);
  log.info("extracting with " + std::to_string(options.workers) + " " +
           (ex.scheduler.empty() ? std::string("local") : ex.scheduler) + " worker" +
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
  result.blocks = {{"block_size", extraction.block_size}, {"leaves", report.leaves}, {"merges", report.merge}};
  result.statistics = nlohmann::json::parse(report.to_json());
  result.statistics["peak_rss_kb"] = result.peak_rss_kb;
  if (report.skipped_leaves == 0) warn_if_empty(result, extraction, context, log); // a resumed run may add nothing
  store.end_run(result.run, result.statistics.dump());
  return result;
}

} // namespace geotandem::workflow
