// geotandem: one executable, one subcommand per use. main builds the world (logger, cancel token,
// signal handling) and passes it down; nothing is registered by static initialisers.

#include <csignal>
#include <iostream>

#include "command.hpp"
#include "geotandem/core/error.hpp"

namespace {

std::atomic<bool>* g_cancel_flag = nullptr; // only touched by the signal handler

extern "C" void on_interrupt(int) {
  if (g_cancel_flag) g_cancel_flag->store(true, std::memory_order_relaxed);
}

} // namespace

int main(int argc, char** argv) {
  using namespace geotandem;
  Logger log(std::cerr);
  app::Context context{log, CancelToken{}};

  CLI::App cli{"geotandem: geobody inventories from seismic cubes.\n"
               "Computes seismic attributes, extracts their isosurfaces with the extended tandem algorithm\n"
               "(marching cubes interleaved with edge-collapse simplification), and stores every surface\n"
               "component in an indexed component store.",
               "geotandem"};
  cli.require_subcommand(1);
  cli.set_version_flag("--version", "geotandem 0.1.0");
  std::string level = "info";
  cli.add_option("--log-level", level, "debug, info, warning, error or quiet")->capture_default_str();
  cli.add_flag("-q,--quiet", context.quiet, "no progress output");

  app::Runner run;
  app::add_synth_command(cli, context, run);
  app::add_info_command(cli, context, run);
  app::add_extract_command(cli, context, run);
  app::add_store_command(cli, context, run);
  app::add_plugins_command(cli, context, run);
  app::add_validate_command(cli, context, run);
  app::add_workflow_command(cli, context, run);
  app::add_worker_command(cli, context, run);

  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 prints the message (or the help text); any usage error exits 2, like InvalidArgument.
    return cli.exit(e) == 0 ? 0 : 2;
  }

  g_cancel_flag = context.cancel.raw_flag();
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  try {
    log.set_level(parse_log_level(level));
    return run();
  } catch (const Error& e) {
    std::cerr << "geotandem: error: " << e.what() << '\n';
    return e.exit_code();
  } catch (const std::exception& e) {
    std::cerr << "geotandem: internal error: " << e.what()
              << " (this is a bug; please report it with the command line that caused it)\n";
    return 70;
  }
}
