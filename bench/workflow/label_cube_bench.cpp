// The label cube at n^3 against the extraction's own time (issue 54): an analytic cube generated on
// the fly (nothing read from disk), extracted in this process into a store, then every component
// labelled and written as raw float32 beside it (4 n^3 bytes of disk). Prints each phase's wall
// time and peak resident memory (VmHWM, reset between the phases through /proc/self/clear_refs).
//
// usage: bench_label_cube [n=1024] [block_size=128] [directory=/tmp]

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include "../bench_args.hpp"
#include "geotandem/core/log.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "geotandem/workflow/extract_step.hpp"
#include "geotandem/workflow/label_cube.hpp"

namespace {

using namespace geotandem;
using Clock = std::chrono::steady_clock;

long peak_kib() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stol(line.substr(6));
  return 0;
}

void reset_peak() {
  std::ofstream("/proc/self/clear_refs") << "5"; // VmHWM := VmRSS
}

// CPU time of this process (all threads): steadier than wall time on a shared machine.
double cpu_seconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

int run(int argc, char** argv) {
  bench::Args args(argc, argv, "bench_label_cube [n=1024] [block_size=128] [directory=/tmp]");
  const std::int64_t n = args.integer(1, 1024, 8);
  const std::int64_t block = args.integer(2, 128, 0);
  const std::filesystem::path dir =
      std::filesystem::path(args.text(3, "/tmp")) / ("bench_label_cube." + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  synth::AnalyticOptions o;
  o.shape = {n, n, n};
  std::shared_ptr<const volume::Volume> cube = synth::make_analytic(o);

  std::ostringstream sink;
  Logger log{sink, LogLevel::warning};
  NullProgress progress;
  CancelToken cancel;
  reset_peak();
  const long base = peak_kib();
  auto store = store::ComponentStore::create((dir / "store").string(), cube->geometry());
  workflow::ExtractionOptions s;
  s.iso = static_cast<float>(synth::analytic_iso);
  s.block_size = block;
  auto t = Clock::now();
  double c = cpu_seconds();
  const auto r = workflow::extract_to_store(*cube, store, s, workflow::ExecutionContext{}, log, progress, cancel);
  const double extract_s = seconds_since(t), extract_cpu = cpu_seconds() - c;
  const long extract_peak = peak_kib();
  std::vector<std::uint64_t> keys;
  for (const auto& row : store.query())
    keys.push_back(row.key);

  reset_peak();
  workflow::LabelSettings ls;
  ls.iso = s.iso;
  t = Clock::now();
  c = cpu_seconds();
  const auto out = workflow::write_label_cube(cube, ls, keys, {}, (dir / "labels.raw").string(), false, {}, "bench",
                                              nullptr, cancel);
  const double label_s = seconds_since(t), label_cpu = cpu_seconds() - c;
  const long label_peak = peak_kib();
  std::printf("analytic %lld^3, %llu components, blocks of %lld cells, one process\n", static_cast<long long>(n),
              static_cast<unsigned long long>(r.components), static_cast<long long>(block));
  std::printf("extraction:  %8.2f s (CPU %.2f s)  peak RSS %7.1f MiB (%.1f MiB before)\n", extract_s, extract_cpu,
              extract_peak / 1024.0, base / 1024.0);
  std::printf(
      "label cube:  %8.2f s (CPU %.2f s)  peak RSS %7.1f MiB  (pass 1 %.2f s, pass 2 + writing %.2f s; %zu bodies)\n",
      label_s, label_cpu, label_peak / 1024.0, out.seconds_label, out.seconds_write, out.bodies.size());
  std::printf("ratio label/extraction: %.2f wall, %.2f CPU\n", label_s / extract_s, label_cpu / extract_cpu);
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_label_cube: %s\n", e.what());
    return 1;
  }
}
