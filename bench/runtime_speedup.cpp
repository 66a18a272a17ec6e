// bench_runtime_speedup: the manager/worker runtime on an analytic cube, against the in-process
// block route: wall time with 1 and 2 local workers (the speed-up), partial-surface bytes per
// merge, peak RSS of the workers and of the manager, the manager's CPU share.
//   bench_runtime_speedup GEOTANDEM_EXECUTABLE [edge=256] [block=64] [workers=1,2]
// Prints one line per configuration. Not a test: figures only.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

#include "bench_args.hpp"
#include "geotandem/core/log.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/runtime/manager.hpp"
#include "geotandem/store/local_sink.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "geotandem/tandem/blocks.hpp"
#include "geotandem/tandem/marching_cubes.hpp"

using namespace geotandem;
namespace fs = std::filesystem;

int bench_main(int argc, char** argv) {
  const geotandem::bench::Args args(argc, argv,
                                    "bench_runtime_speedup GEOTANDEM_EXECUTABLE [edge=256] [block=64] [workers=1,2]");
  if (args.size() < 1) args.fail(1, "is missing: the geotandem executable that runs the workers");
  const std::string exe = args.text(1, "");
  const std::int64_t edge = args.integer(2, 256, 2);
  const std::int64_t block = args.integer(3, 64, 1);
  const std::vector<std::int64_t> counts = args.integers(4, "1,2", 1);
  synth::AnalyticOptions a;
  a.shape = {edge, edge, edge};
  a.seed = 1;
  const auto cube = synth::make_analytic(a);
  const std::string description = R"({"kind":"analytic","shape":[)" + std::to_string(edge) + "," +
                                  std::to_string(edge) + "," + std::to_string(edge) + R"(],"seed":1})";
  const fs::path root = fs::temp_directory_path() / ("geotandem_bench_runtime_" + std::to_string(getpid()));
  NullProgress progress;
  CancelToken cancel;

  std::printf("analytic cube %lld^3, leaves of %lld cells\n", static_cast<long long>(edge),
              static_cast<long long>(block));
  double one = 0;
  for (const std::int64_t workers : counts) {
    const std::string n = std::to_string(workers);
    auto store = store::ComponentStore::create(root / ("w" + n), cube->geometry());
    runtime::ManagerOptions options;
    options.settings.volume = description;
    options.settings.store = (root / ("w" + n)).string();
    options.settings.extraction.block_size = block;
    options.settings.extraction.iso = 0.5f;
    options.settings.run = store.begin_run("{}");
    options.workers = static_cast<std::size_t>(workers);
    options.worker_command = {exe, "-q", "--log-level", "warning", "worker"};
    runtime::LocalLauncher launcher;
    runtime::Manager manager(options, store, &launcher, Logger::null(), progress, cancel);
    const runtime::ManagerReport r = manager.run();
    if (workers == 1) one = r.seconds;
    std::printf("%2s worker(s): %7.2f s (speed-up %.2fx), %llu components, %llu sends, %.1f KiB per merge "
                "(largest %.1f KiB), worker peak RSS %lld MiB, manager peak RSS %lld MiB, manager CPU %.1f %% "
                "of the wall time; worker seconds: extract %.2f, merge %.2f, finish %.2f\n",
                n.c_str(), r.seconds, one > 0 ? one / r.seconds : 0.0, static_cast<unsigned long long>(r.components),
                static_cast<unsigned long long>(r.send),
                r.send ? static_cast<double>(r.surface_bytes) / 1024.0 / static_cast<double>(r.send) : 0.0,
                static_cast<double>(r.largest_surface) / 1024.0, static_cast<long long>(r.worker_peak_rss_kb / 1024),
                static_cast<long long>(r.manager_peak_rss_kb / 1024), 100.0 * r.manager_cpu_seconds / r.seconds,
                r.seconds_extract, r.seconds_merge, r.seconds_finish);
  }
  // In process last, so that the manager's peak RSS above is the manager's own.
  {
    auto store = store::ComponentStore::create(root / "inproc", cube->geometry());
    store::LocalSink sink(store);
    tandem::TandemOptions o;
    o.iso = 0.5f;
    const auto t = std::chrono::steady_clock::now();
    const auto s = tandem::extract_blocks(*cube, tandem::cube_cells(cube->geometry().shape), block, o, &sink);
    sink.close();
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    std::printf("in process  : %7.2f s, %llu components, %llu merges, %.1f KiB shipped per merge\n", sec,
                static_cast<unsigned long long>(sink.committed()), static_cast<unsigned long long>(s.merges),
                s.merges ? static_cast<double>(s.wire_bytes) / 1024.0 / static_cast<double>(s.merges) : 0.0);
  }
  fs::remove_all(root);
  return 0;
}

int main(int argc, char** argv) {
  return geotandem::bench::guarded_main("bench_runtime_speedup", [&] { return bench_main(argc, argv); });
}
