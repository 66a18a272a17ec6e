// geotandem: one executable, one subcommand per use. main builds the world (logger, cancel token,
// signal handling) and passes it down; nothing is registered by static initialisers.

#include <malloc.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <new>
#include <stdexcept>

#include "command.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/core/interrupt.hpp"
#include "geotandem/volume/size_guard.hpp"

namespace {

// The size of the last allocation that failed, for the "out of memory" message.
std::atomic<std::size_t> g_failed_allocation{0};

} // namespace

// operator new records the size it could not get (the standard bad_alloc carries none); the
// library's operator delete frees with std::free, as for its own operator new. Left to the
// sanitizers' own allocator in sanitizer builds.
#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
void* operator new(std::size_t size) {
  if (size == 0) size = 1;
  for (;;) {
    if (void* p = std::malloc(size)) return p;
    std::new_handler handler = std::get_new_handler();
    if (!handler) {
      g_failed_allocation.store(size, std::memory_order_relaxed);
      throw std::bad_alloc();
    }
    handler();
  }
}
void* operator new[](std::size_t size) {
  return ::operator new(size);
}
#endif

namespace {

// glibc serves an allocation above its mmap threshold with a mapping of its own, given back to the
// system when freed; below it, from the heap, whose free pages stay resident (the heap's top is
// given back beyond the trim threshold). By default the mmap threshold starts at 128 KiB and rises
// to the size of every mapped block freed, up to 32 MiB (the trim threshold to twice that), so
// after the first leaves of an extraction most of the surfaces' arrays live in the heap, and what
// the leaves and merges free there stays in the peak. geotandem fixes the mmap threshold at 4 MiB
// and the trim threshold at 16 MiB: the large arrays (the top merges' surfaces and records) live
// in mappings of their own and go back when freed, while the leaves' arrays, allocated and freed
// by the thousand, reuse the heap's pages instead of faulting fresh ones in each time. Analytic
// 1024^3, extract only (docs/algorithm.md, "Memory"): glibc's default 366 MiB peak in 3:30; a
// threshold of 1 MiB 281 MiB in 4:58 (5.5 M page faults against 0.4 M); these two 287 MiB in 3:55.
// The paper's cube at 1/16 with two workers: 494.6 s wall with 1 MiB, 265.9 s with these. A
// threshold the user set (GLIBC_TUNABLES, MALLOC_MMAP_THRESHOLD_, MALLOC_TRIM_THRESHOLD_) is left
// as it is.
void fix_malloc_thresholds() {
#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  auto user_set = [&](const char* variable, const char* tunable) {
    return std::getenv(variable) != nullptr || (tunables && std::strstr(tunables, tunable));
  };
  if (!user_set("MALLOC_MMAP_THRESHOLD_", "mmap_threshold")) mallopt(M_MMAP_THRESHOLD, 4 << 20);
  if (!user_set("MALLOC_TRIM_THRESHOLD_", "trim_threshold")) mallopt(M_TRIM_THRESHOLD, 16 << 20);
#endif
}

} // namespace

int main(int argc, char** argv) {
  using namespace geotandem;
  fix_malloc_thresholds();
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
  CLI::Option* level_option =
      cli.add_option("--log-level", level, "debug, info, warning, error or quiet (default: info; warning with -q)")
          ->capture_default_str();
  cli.add_flag("-q,--quiet", context.quiet,
               "no progress output and no info lines: warnings, errors and the summary only (an explicit "
               "--log-level still applies)");

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

  install_interrupt_handling(context.cancel);
  try {
    // -q silences the info lines too, unless the level was asked for.
    if (context.quiet && level_option->count() == 0) level = "warning";
    log.set_level(parse_log_level(level));
    context.log_level = level;
    return run();
  } catch (const Error& e) {
    std::cerr << "geotandem: error: " << e.what() << '\n';
    return e.exit_code();
  } catch (const std::bad_alloc&) {
    // Out of memory is a size the machine cannot hold, not a bug: say how much was asked.
    const std::size_t asked = g_failed_allocation.load(std::memory_order_relaxed);
    std::cerr << "geotandem: error: out of memory"
              << (asked ? " (an allocation of " + volume::byte_size_text(asked) + " failed)" : std::string())
              << " (use a smaller cube or box, a --block-size, or a machine with more memory)\n";
    return 5;
  } catch (const std::length_error& e) {
    std::cerr << "geotandem: error: a size larger than this machine can hold was asked (" << e.what()
              << ") (check the cube's shape; use a smaller cube or box)\n";
    return 5;
  } catch (const std::filesystem::filesystem_error& e) {
    // A path the user gave that cannot be created, read or removed.
    std::cerr << "geotandem: error: " << e.path1().string() << ": " << e.code().message()
              << " (check the path and its permissions)\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "geotandem: internal error: " << e.what()
              << " (this is a bug; please report it with the command line that caused it)\n";
    return 70;
  }
}
