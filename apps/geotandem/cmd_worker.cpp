// geotandem worker --connect ENDPOINT --token T: one worker of the manager/worker runtime. The
// manager starts it (locally with --workers N, or through a cluster scheduler); it rebuilds the
// input volume from the description the manager sends and obeys until told to finish.

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <optional>

#include "command.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/runtime/worker.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "geotandem/volume/crs.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/workflow/chain.hpp"
#include "plugins_setup.hpp"

namespace geotandem::app {

std::string self_executable() {
  std::error_code ec;
  const auto path = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw IoError("cannot find this executable (/proc/self/exe): " + ec.message());
  return path.string();
}

std::vector<std::string> worker_command(const Context& context) {
  if (context.log_level == "info") return {self_executable(), "worker"};
  return {self_executable(), "--log-level", context.log_level, "worker"};
}

std::string describe_cube_file(const std::string& path, const std::string& nan, std::optional<float> no_data,
                               const std::string& variable, const volume::SegyOptions& segy, const std::string& crs,
                               const std::string& hint, bool fill_highest) {
  nlohmann::json d{{"kind", "file"},
                   {"path", std::filesystem::absolute(path).string()},
                   {"nan", nan},
                   {"variable", variable},
                   {"segy", volume::to_json(segy)}};
  if (no_data) d["no_data"] = *no_data;
  if (!crs.empty()) d["crs"] = crs; // --crs as given: the workers' volume says the manager's CRS
  if (!hint.empty()) d["reopen_hint"] = hint;
  if (fill_highest) d["fill"] = "highest";
  return d.dump();
}

std::shared_ptr<const volume::Volume> open_described_volume(const std::string& description, Logger& log) {
  nlohmann::json d;
  try {
    d = nlohmann::json::parse(description);
    const std::string kind = d.at("kind").get<std::string>();
    if (kind == "file") {
      volume::OpenOptions open;
      open.nan_policy = volume::parse_nan_policy(d.at("nan").get<std::string>());
      open.variable = d.at("variable").get<std::string>();
      if (d.contains("no_data")) open.no_data = d.at("no_data").get<float>();
      if (d.contains("segy")) open.segy = volume::segy_options_from_json(d["segy"]);
      open.reopen_hint = d.value("reopen_hint", "");
      if (d.contains("crs")) open.crs = volume::parse_crs(d.at("crs").get<std::string>());
      // Missing samples filled for an extraction of the side below stay outside (cmd_extract.cpp).
      if (d.value("fill", "") == "highest") open.fill_value = std::numeric_limits<float>::max();
      return volume::open_volume(d.at("path").get<std::string>(), open);
    }
    if (kind == "analytic") {
      synth::AnalyticOptions options;
      const auto shape = d.at("shape").get<std::vector<std::int64_t>>();
      if (shape.size() != 3) throw InvalidArgument("volume description: shape needs three sizes");
      options.shape = {shape[0], shape[1], shape[2]};
      options.seed = d.at("seed").get<std::uint64_t>();
      return synth::make_analytic(options);
    }
    if (kind == "chain") { // a recipe's input and attribute chain, fused block by block in the worker
      // The registry (and the plugin libraries it loaded) lives as long as the volume.
      struct Held {
        workflow::PluginRegistry registry;
        std::shared_ptr<const volume::Volume> volume;
      };
      auto held = std::make_shared<Held>(Held{make_plugin_registry(log), nullptr});
      held->volume = workflow::open_chain_volume(workflow::ChainDescription::from_json(d.at("chain")), held->registry);
      return std::shared_ptr<const volume::Volume>(held, held->volume.get());
    }
    throw InvalidArgument("volume description of unknown kind '" + kind + "'", {},
                          "run the same geotandem version on the manager and every worker");
  } catch (const nlohmann::json::exception& e) {
    throw InvalidArgument(std::string("volume description is not valid: ") + e.what(), {},
                          "run the same geotandem version on the manager and every worker");
  }
}

void add_worker_command(CLI::App& app, Context& context, Runner& run) {
  auto options = std::make_shared<runtime::WorkerOptions>();
  auto* cmd = app.add_subcommand(
      "worker", "Run one worker of the manager/worker runtime: connect to the manager, extract, send and merge "
                "blocks as told, write finished components to this worker's shard. Started by 'geotandem extract "
                "--workers N' or by a cluster scheduler; not usually run by hand.");
  cmd->add_option("--connect", options->endpoint, "the manager's endpoint, e.g. tcp://10.0.0.5:5555")->required();
  cmd->add_option("--token", options->token, "the launch token the manager issued (names this worker and its shard)")
      ->required();
  auto timeout = std::make_shared<double>(10.0);
  cmd->add_option("--manager-timeout", *timeout, "seconds of silence after which the manager is taken for gone")
      ->capture_default_str()
      ->check(positive());
  cmd->callback([options, timeout, &context, &run] {
    run = [options, timeout, &context] {
      // Under a billion seconds (31 years): inf means never, and the milliseconds must fit.
      options->manager_timeout = std::chrono::milliseconds(static_cast<std::int64_t>(std::min(*timeout, 1e9) * 1000));
      Logger& log = context.log;
      try {
        return runtime::run_worker(
            *options, [&log](const std::string& d) { return open_described_volume(d, log); }, log, context.cancel);
      } catch (const Cancelled&) {
        // SIGTERM or SIGINT: its manager stopped it (at the end of a run, one it had given up on,
        // e.g. frozen for a while), its scheduler cancelled the job, or Ctrl-C reached the whole
        // process group. A worker told to stop is not an error; the manager reports the run.
        log.info("worker " + options->token + ": stopped by a signal; the work it finished is kept");
        return 130;
      }
    };
  });
}

} // namespace geotandem::app
