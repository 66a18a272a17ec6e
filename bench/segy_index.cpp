// bench_segy_index: opening an unsorted SEG-Y file through the trace index (issue 54, part 4).
//
// Generates a post-stack file of NI x NJ traces (default 1000 x 1000 = 1 M traces) of a few IEEE
// samples each, in a random order (and, for comparison, the same traces sorted), then times
// open_volume on it (the pass over every trace header that builds the index), the open of a
// worker given the manager's index (Volume::reopen_hint), and a box read through the index; peak
// memory (VmHWM, reset before each open) beside the file's size. The files are written under DIR
// (default /tmp) and removed at the end.
//
// usage: bench_segy_index [ni=1000] [nj=1000] [samples=4] [dir=/tmp]

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "geotandem/volume/io.hpp"
#include "page_cache.hpp"

namespace {

using Clock = std::chrono::steady_clock;

void put16(unsigned char* p, int v) {
  p[0] = static_cast<unsigned char>((v >> 8) & 0xFF);
  p[1] = static_cast<unsigned char>(v & 0xFF);
}
void put32(unsigned char* p, std::int32_t v) {
  const auto u = static_cast<std::uint32_t>(v);
  for (int b = 0; b < 4; ++b)
    p[b] = static_cast<unsigned char>((u >> (24 - 8 * b)) & 0xFF);
}
void put_float(unsigned char* p, float v) {
  std::uint32_t u;
  std::memcpy(&u, &v, 4);
  put32(p, static_cast<std::int32_t>(u));
}

// A big-endian SEG-Y rev 1 file of IEEE samples, its traces in `order` (bin numbers, row-major),
// line numbers at 189/193, coordinates at 181/185 with scalar -100. Written in 4 MiB pieces: the
// generator holds the order (4 bytes per trace) and one piece.
void generate(const std::string& path, int nj, int ns, const std::vector<std::int32_t>& order) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  std::vector<unsigned char> head(3600, 0);
  std::memset(head.data(), ' ', 3200);
  std::memcpy(head.data(), "C01 bench_segy_index: unsorted traces", 37);
  put16(&head[3216], 4000);
  put16(&head[3220], ns);
  put16(&head[3224], 5);
  put16(&head[3500], 0x0100);
  out.write(reinterpret_cast<const char*>(head.data()), static_cast<std::streamsize>(head.size()));
  const std::size_t trace_bytes = 240 + 4 * static_cast<std::size_t>(ns);
  const std::size_t per_piece = std::max<std::size_t>(1, (4u << 20) / trace_bytes);
  std::vector<unsigned char> piece;
  for (std::size_t first = 0; first < order.size(); first += per_piece) {
    const std::size_t count = std::min(per_piece, order.size() - first);
    piece.assign(count * trace_bytes, 0);
    for (std::size_t n = 0; n < count; ++n) {
      unsigned char* t = piece.data() + n * trace_bytes;
      const int bin = order[first + n], i = bin / nj, j = bin % nj;
      put32(t + 0, static_cast<std::int32_t>(first + n + 1));
      put16(t + 70, -100);
      put16(t + 114, ns);
      put16(t + 116, 4000);
      put32(t + 180, 50000000 + 2500 * i);
      put32(t + 184, 670000000 + 2500 * j);
      put32(t + 188, 1000 + i);
      put32(t + 192, 2000 + j);
      for (int k = 0; k < ns; ++k)
        put_float(t + 240 + 4 * k,
                  static_cast<float>(i) + 0.001f * static_cast<float>(j) + 0.5f * static_cast<float>(k));
    }
    out.write(reinterpret_cast<const char*>(piece.data()), static_cast<std::streamsize>(piece.size()));
  }
  if (!out) throw std::runtime_error("cannot write " + path);
}

double status_mib(const char* key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::string prefix = std::string(key) + ":";
  while (std::getline(in, line))
    if (line.rfind(prefix, 0) == 0) return std::stod(line.substr(prefix.size())) / 1024.0;
  return -1.0;
}

bool reset_peak() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.flush();
  return static_cast<bool>(out);
}

struct Opened {
  std::unique_ptr<geotandem::volume::Volume> volume;
  double seconds = 0.0, peak_mib = 0.0, rss_before = 0.0;
};

Opened timed_open(const std::string& path, const std::string& hint = {}) {
  geotandem::volume::OpenOptions options;
  options.reopen_hint = hint;
  Opened o;
  const bool reset = reset_peak();
  o.rss_before = status_mib("VmRSS");
  const auto t0 = Clock::now();
  o.volume = geotandem::volume::open_volume(path, options);
  o.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  o.peak_mib = reset ? status_mib("VmHWM") : -1.0;
  return o;
}

std::string detail(const geotandem::volume::Volume& v, const std::string& key) {
  for (const auto& d : v.format_details())
    if (d.key == key) return d.value;
  return {};
}

} // namespace

int main(int argc, char** argv) {
  return geotandem::bench::guarded_main("bench_segy_index", [&] {
    geotandem::bench::Args args(argc, argv, "bench_segy_index [ni=1000] [nj=1000] [samples=4] [dir=/tmp]");
    const int ni = static_cast<int>(args.integer(1, 1000, 1));
    const int nj = static_cast<int>(args.integer(2, 1000, 1));
    const int ns = static_cast<int>(args.integer(3, 4, 1));
    const std::string dir = args.text(4, "/tmp");
    const std::size_t traces = static_cast<std::size_t>(ni) * static_cast<std::size_t>(nj);
    const std::string unsorted = dir + "/bench_segy_index_unsorted.sgy", sorted = dir + "/bench_segy_index_sorted.sgy";
    struct Cleanup {
      std::vector<std::string> files;
      ~Cleanup() {
        for (const auto& f : files)
          std::filesystem::remove(f);
      }
    } cleanup{{unsorted, sorted}};
    {
      std::vector<std::int32_t> order(traces);
      std::iota(order.begin(), order.end(), 0);
      auto t0 = Clock::now();
      generate(sorted, nj, ns, order);
      std::shuffle(order.begin(), order.end(), std::mt19937_64(54));
      generate(unsorted, nj, ns, order);
      std::printf("generated %zu traces of %d samples (%d x %d), unsorted and sorted: %.1f MiB each, %.2f s\n", traces,
                  ns, ni, nj, static_cast<double>(std::filesystem::file_size(unsorted)) / (1 << 20),
                  std::chrono::duration<double>(Clock::now() - t0).count());
    }
    std::printf("index memory: 4 bytes per bin kept (%.1f MiB), 12 bytes per trace while the pass runs (%.1f MiB)\n",
                4.0 * static_cast<double>(traces) / (1 << 20), 12.0 * static_cast<double>(traces) / (1 << 20));
    for (const bool cold : {false, true}) {
      if (cold && !geotandem::bench::evict(unsorted)) {
        std::printf("(could not drop the file from the page cache: no cold figure)\n");
        continue;
      }
      Opened o = timed_open(unsorted);
      std::printf("unsorted, %s cache: open (index built) %.3f s, %.2f us per trace; peak RSS %.1f MiB (%.1f MiB "
                  "before the open, +%.1f MiB)\n",
                  cold ? "cold" : "warm", o.seconds, 1e6 * o.seconds / static_cast<double>(traces), o.peak_mib,
                  o.rss_before, o.peak_mib - o.rss_before);
      if (!cold) std::printf("  sorting: %s\n", detail(*o.volume, "sorting").c_str());
    }
    {
      Opened manager = timed_open(unsorted);
      const std::string hint = manager.volume->reopen_hint();
      manager.volume.reset();
      Opened worker = timed_open(unsorted, hint);
      std::printf("worker open with the manager's index (hint of %.1f MiB): %.3f s; peak RSS +%.1f MiB\n",
                  static_cast<double>(hint.size()) / (1 << 20), worker.seconds, worker.peak_mib - worker.rss_before);
      const geotandem::volume::Box box{{ni / 4, nj / 4, 0}, {std::min(ni, ni / 4 + 64), std::min(nj, nj / 4 + 64), ns}};
      auto t0 = Clock::now();
      const std::vector<float> samples = worker.volume->read(box);
      const double s = std::chrono::duration<double>(Clock::now() - t0).count();
      const auto i = box.lo[0], j = box.lo[1];
      const bool right = samples[0] == static_cast<float>(i) + 0.001f * static_cast<float>(j);
      std::printf("box of %lld traces read through the index: %.3f s (%s)\n", static_cast<long long>(box.count() / ns),
                  s, right ? "first sample right" : "FIRST SAMPLE WRONG");
    }
    {
      Opened o = timed_open(sorted);
      std::printf("sorted (for comparison; found from a few headers): open %.3f s; peak RSS +%.1f MiB; sorting: %s\n",
                  o.seconds, o.peak_mib - o.rss_before, detail(*o.volume, "sorting").c_str());
    }
    return 0;
  });
}
