// Memory of the three extraction routes on one block (the seed's figure 11): brute force (extract
// everything, then simplify once), the tandem without dumping (simplify layer by layer, keep every
// component to the end) and the tandem with dumping (hand finished components over during the
// sweep). Each route runs in a forked child so that peak RSS figures (VmHWM) do not mix.
//
//   bench_tandem_memory [N=512] [--svg PATH=tandem_memory.svg] [--e0 X=0.5] [--axis A=0]
//                       [--modes brute,tandem,tandem-dump] [--seed S=1] [--no-guarantee]
//
// --no-guarantee: without the E0 guarantee (SimplifyOptions::guarantee_distance), for its cost.
//
// The cube is the procedural analytic synthetic cube of N^3 samples (make_analytic: thousands of
// planted geobodies and tiny bubbles, docs/synthetic.md), computed cross-section by cross-section
// as marching cubes asks for it: no sample array is held, so the peak RSS is the algorithm's.
// Printed: per route, peak RSS, input and output triangles, most triangles held, CPU time, input
// triangles per CPU second (one thread: per core) and collapses per CPU second of simplification;
// the triangles held after every layer (a sample of the layers as a table, all of them in the
// SVG plot); the ratio of the tandem-with-dumping peak RSS to the brute-force one.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "bench_args.hpp"
#include "geotandem/mesh/component.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "geotandem/tandem/tandem.hpp"

using namespace geotandem;

namespace {

// A figure from /proc/self/status in MiB ("VmHWM", "VmRSS"); -1 when absent.
double status_mib(const char* key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::string prefix = std::string(key) + ":";
  while (std::getline(in, line))
    if (line.rfind(prefix, 0) == 0) return std::atof(line.c_str() + prefix.size()) / 1024.0;
  return -1.0;
}

// Resets VmHWM to the current RSS (Linux >= 4.0); false when not permitted.
bool reset_peak_rss() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.flush();
  return static_cast<bool>(out);
}

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

class CountingSink final : public mesh::ComponentSink {
public:
  void commit(const mesh::Component& c) override {
    ++components;
    triangles += c.surface.triangle_count();
  }
  std::uint64_t components = 0;
  std::uint64_t triangles = 0;
};

// What a child reports through its pipe.
struct Summary {
  // seconds_simplify and seconds_phases (extract + insert + simplify + dump) are wall-clock
  // times of the route's phases; the simplification's CPU share is scaled from them.
  double rss_start_mib = 0, peak_mib = 0, cpu = 0, seconds_simplify = 0, seconds_phases = 0;
  std::uint64_t input_triangles = 0, output_triangles = 0, components = 0, collapses = 0, peak_triangles = 0;
  std::uint64_t layers = 0;
  int peak_reset = 0;
};

struct Result {
  std::string mode;
  Summary s;
  std::vector<std::uint64_t> in_memory; // triangles held after each layer
  std::vector<std::int64_t> ranks;
};

void write_all(int fd, const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) std::_Exit(3);
    p += n;
    size -= static_cast<std::size_t>(n);
  }
}

bool read_all(int fd, void* data, std::size_t size) {
  char* p = static_cast<char*>(data);
  while (size > 0) {
    const ssize_t n = ::read(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

// The child: builds the cube, runs one route, writes a Summary and the per-layer figures.
[[noreturn]] void child(int fd, const std::string& mode, const synth::AnalyticOptions& cube_options,
                        const tandem::TandemOptions& base) {
  try {
    const auto cube = synth::make_analytic(cube_options);
    tandem::TandemOptions options = base;
    options.dump = mode == "tandem-dump";
    Summary s;
    s.peak_reset = reset_peak_rss() ? 1 : 0;
    s.rss_start_mib = status_mib("VmRSS");
    CountingSink sink;
    const double t0 = cpu_seconds();
    const tandem::TandemStats stats = tandem::extract_block(*cube, tandem::cube_cells(cube->geometry().shape), options,
                                                            &sink, nullptr, mode == "brute");
    s.cpu = cpu_seconds() - t0;
    s.peak_mib = status_mib("VmHWM");
    s.input_triangles = stats.counters.input_triangles;
    s.output_triangles = sink.triangles;
    s.components = sink.components;
    s.collapses = stats.counters.collapses;
    s.peak_triangles = stats.peak_triangles;
    s.seconds_simplify = stats.final_pass.seconds_simplify;
    s.seconds_phases = stats.final_pass.seconds_simplify + stats.final_pass.seconds_dump;
    for (const tandem::LayerStats& l : stats.layers) {
      s.seconds_simplify += l.seconds_simplify;
      s.seconds_phases += l.seconds_extract + l.seconds_insert + l.seconds_simplify + l.seconds_dump;
    }
    s.layers = stats.layers.size();
    write_all(fd, &s, sizeof s);
    for (const tandem::LayerStats& l : stats.layers) {
      const std::uint64_t row[2] = {static_cast<std::uint64_t>(l.rank), l.triangles_in_memory};
      write_all(fd, row, sizeof row);
    }
    ::close(fd);
    std::_Exit(0);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", mode.c_str(), e.what());
    std::_Exit(2);
  }
}

Result run_mode(const std::string& mode, const synth::AnalyticOptions& cube_options,
                const tandem::TandemOptions& options) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("pipe failed");
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    ::close(fds[0]);
    child(fds[1], mode, cube_options, options);
  }
  ::close(fds[1]);
  Result r;
  r.mode = mode;
  bool ok = read_all(fds[0], &r.s, sizeof r.s);
  for (std::uint64_t l = 0; ok && l < r.s.layers; ++l) {
    std::uint64_t row[2];
    ok = read_all(fds[0], row, sizeof row);
    r.ranks.push_back(static_cast<std::int64_t>(row[0]));
    r.in_memory.push_back(row[1]);
  }
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!ok || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("route " + mode + " failed (child status " + std::to_string(status) + ")");
  return r;
}

// --- SVG line plot: triangles in memory against the layer, log y axis ---------------------------

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

void write_svg(const std::string& path, const std::vector<Result>& results, const std::string& title) {
  const double W = 820, H = 520, left = 90, right = 200, top = 50, bottom = 70;
  const double pw = W - left - right, ph = H - top - bottom;
  std::int64_t x_max = 1;
  std::uint64_t y_top = 10, y_low = std::numeric_limits<std::uint64_t>::max();
  for (const Result& r : results) {
    for (std::int64_t k : r.ranks)
      x_max = std::max(x_max, k);
    for (std::uint64_t y : r.in_memory) {
      y_top = std::max(y_top, y);
      y_low = std::min(y_low, std::max<std::uint64_t>(y, 1));
    }
  }
  const int dec_hi = static_cast<int>(std::ceil(std::log10(static_cast<double>(y_top))));
  // From the decade of the smallest count; a layer holding nothing is drawn at 1.
  const int dec_lo =
      std::min(dec_hi - 1, static_cast<int>(std::floor(std::log10(static_cast<double>(std::min(y_low, y_top))))));
  auto X = [&](double k) { return left + pw * k / static_cast<double>(x_max); };
  auto Y = [&](double v) {
    const double l = std::max(std::log10(std::max(v, 1.0)), static_cast<double>(dec_lo));
    return top + ph * (1.0 - (l - dec_lo) / (dec_hi - dec_lo));
  };
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
      << "\" font-family=\"sans-serif\" font-size=\"13\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << left + pw / 2 << "\" y=\"28\" text-anchor=\"middle\" font-size=\"16\">" << title
      << "</text>\n";
  // Grid and ticks: decades (labelled) and 2..9 (faint) on y; about 8 steps on x.
  for (int d = dec_lo; d <= dec_hi; ++d) {
    const double y = Y(std::pow(10.0, d));
    svg << "<line x1=\"" << left << "\" x2=\"" << left + pw << "\" y1=\"" << y << "\" y2=\"" << y
        << "\" stroke=\"#ccc\"/>\n<text x=\"" << left - 8 << "\" y=\"" << y + 4 << "\" text-anchor=\"end\">10"
        << "<tspan dy=\"-6\" font-size=\"10\">" << d << "</tspan></text>\n";
    for (int m = 2; m < 10 && d < dec_hi; ++m) {
      const double ym = Y(m * std::pow(10.0, d));
      svg << "<line x1=\"" << left << "\" x2=\"" << left + pw << "\" y1=\"" << ym << "\" y2=\"" << ym
          << "\" stroke=\"#eee\"/>\n";
    }
  }
  const double step = std::max(1.0, std::pow(10.0, std::floor(std::log10(static_cast<double>(x_max) / 8.0))));
  const double x_step = static_cast<double>(x_max) / step > 16 ? 5 * step : (x_max / step > 8 ? 2 * step : step);
  for (double k = 0; k <= static_cast<double>(x_max) + 0.5; k += x_step)
    svg << "<line x1=\"" << X(k) << "\" x2=\"" << X(k) << "\" y1=\"" << top << "\" y2=\"" << top + ph
        << "\" stroke=\"#eee\"/>\n<text x=\"" << X(k) << "\" y=\"" << top + ph + 18 << "\" text-anchor=\"middle\">"
        << fmt("%.0f", k) << "</text>\n";
  svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph
      << "\" fill=\"none\" stroke=\"black\"/>\n"
      << "<text x=\"" << left + pw / 2 << "\" y=\"" << H - 22
      << "\" text-anchor=\"middle\">layer (rank along the extraction axis)</text>\n"
      << "<text transform=\"translate(24," << top + ph / 2
      << ") rotate(-90)\" text-anchor=\"middle\">triangles in memory (log scale)</text>\n";
  const char* colours[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd"};
  for (std::size_t r = 0; r < results.size(); ++r) {
    const char* colour = colours[r % 4];
    svg << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"2\" points=\"";
    for (std::size_t l = 0; l < results[r].ranks.size(); ++l)
      svg << fmt("%.1f", X(static_cast<double>(results[r].ranks[l]))) << ","
          << fmt("%.1f", Y(static_cast<double>(results[r].in_memory[l]))) << " ";
    svg << "\"/>\n";
    const double ly = top + 20 + 40 * static_cast<double>(r);
    svg << "<line x1=\"" << left + pw + 15 << "\" x2=\"" << left + pw + 45 << "\" y1=\"" << ly << "\" y2=\"" << ly
        << "\" stroke=\"" << colour << "\" stroke-width=\"2\"/>\n<text x=\"" << left + pw + 52 << "\" y=\"" << ly + 4
        << "\">" << results[r].mode << "</text>\n<text x=\"" << left + pw + 52 << "\" y=\"" << ly + 20
        << "\" font-size=\"11\" fill=\"#555\">peak RSS " << fmt("%.0f", results[r].s.peak_mib) << " MiB</text>\n";
  }
  svg << "</svg>\n";
  std::ofstream out(path);
  out << svg.str();
  if (!out) throw std::runtime_error("cannot write " + path);
}

} // namespace

using geotandem::bench::split;

int main(int argc, char** argv) {
  std::int64_t n = 512;
  std::string svg_path = "tandem_memory.svg";
  std::vector<std::string> modes = {"brute", "tandem", "tandem-dump"};
  tandem::TandemOptions options;
  options.iso = static_cast<float>(synth::analytic_iso);
  synth::AnalyticOptions cube;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    const bool has_value = a + 1 < argc;
    if (arg == "--svg" && has_value) {
      svg_path = argv[++a];
    } else if (arg == "--e0" && has_value) {
      options.simplify.max_error = std::atof(argv[++a]);
    } else if (arg == "--axis" && has_value) {
      options.axis = std::atoi(argv[++a]);
    } else if (arg == "--modes" && has_value) {
      modes = split(argv[++a]);
    } else if (arg == "--no-guarantee") {
      options.simplify.guarantee_distance = false; // the seed's algorithm: eps_0 <= E0 only
    } else if (arg == "--seed" && has_value) {
      cube.seed = std::strtoull(argv[++a], nullptr, 10);
    } else if (std::int64_t edge = 0; geotandem::bench::to_integer(arg, 2, edge)) {
      n = edge;
    } else {
      std::fprintf(arg == "--help" ? stdout : stderr,
                   "usage: %s [N=512] [--svg PATH] [--e0 X] [--axis A] [--modes LIST] [--seed S] [--no-guarantee]\n",
                   argv[0]);
      return arg == "--help" ? 0 : 2;
    }
  }
  cube.shape = {n, n, n};
  std::printf("analytic synthetic cube %lld^3 (seed %llu), iso 0.5, E0 %.2f voxel, alpha %.2f, axis %d, one thread "
              "per route, each route in its own process\n",
              static_cast<long long>(n), static_cast<unsigned long long>(cube.seed), options.simplify.max_error,
              options.simplify.isotropy, options.axis);
  std::vector<Result> results;
  try {
    for (const std::string& mode : modes) {
      if (mode != "brute" && mode != "tandem" && mode != "tandem-dump") {
        std::fprintf(stderr, "unknown route '%s' (brute, tandem, tandem-dump)\n", mode.c_str());
        return 2;
      }
      results.push_back(run_mode(mode, cube, options));
      const Summary& s = results.back().s;
      std::fprintf(stderr, "  %s done: %.1f s CPU, peak %.0f MiB\n", mode.c_str(), s.cpu, s.peak_mib);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_tandem_memory: %s\n", e.what());
    return 1;
  }

  std::printf("\n%-12s %10s %9s %12s %10s %7s %11s %8s %11s %10s\n", "route", "peak-RSS", "start-RSS", "in-tris",
              "out-tris", "comps", "held-peak", "cpu-s", "Mtri/s/core", "kcoll/s");
  for (const Result& r : results) {
    const Summary& s = r.s;
    // CPU seconds of the simplification: its wall-clock share of the phases times the CPU time
    // (they differ only by preemption on a shared machine).
    const double simplify_cpu = s.seconds_phases > 0 ? s.cpu * s.seconds_simplify / s.seconds_phases : 0.0;
    std::printf("%-12s %7.0f MiB %5.0f MiB %12llu %10llu %7llu %11llu %8.1f %11.3f %10.1f\n", r.mode.c_str(),
                s.peak_mib, s.rss_start_mib, static_cast<unsigned long long>(s.input_triangles),
                static_cast<unsigned long long>(s.output_triangles), static_cast<unsigned long long>(s.components),
                static_cast<unsigned long long>(s.peak_triangles), s.cpu,
                1e-6 * static_cast<double>(s.input_triangles) / s.cpu,
                simplify_cpu > 0 ? 1e-3 * static_cast<double>(s.collapses) / simplify_cpu : 0.0);
    if (!s.peak_reset) std::printf("  (could not reset VmHWM in the child: its peak includes the parent's pages)\n");
  }

  // Triangles held after every layer, a sample of the layers.
  std::printf("\ntriangles in memory after layer k:\n%8s", "layer");
  for (const Result& r : results)
    std::printf(" %14s", r.mode.c_str());
  std::printf("\n");
  const std::size_t layers = results.empty() ? 0 : results.front().ranks.size();
  const std::size_t stride = std::max<std::size_t>(1, layers / 16);
  for (std::size_t l = 0; l < layers; l += stride) {
    std::printf("%8lld", static_cast<long long>(results.front().ranks[l]));
    for (const Result& r : results)
      std::printf(" %14llu", static_cast<unsigned long long>(l < r.in_memory.size() ? r.in_memory[l] : 0));
    std::printf("\n");
  }

  const Result* brute = nullptr;
  const Result* dump = nullptr;
  for (const Result& r : results) {
    if (r.mode == "brute") brute = &r;
    if (r.mode == "tandem-dump") dump = &r;
  }
  if (brute && dump)
    std::printf("\npeak RSS tandem-dump / brute = %.0f / %.0f MiB = %.3f (1/%.1f; target <= 1/10)\n", dump->s.peak_mib,
                brute->s.peak_mib, dump->s.peak_mib / brute->s.peak_mib, brute->s.peak_mib / dump->s.peak_mib);
  try {
    write_svg(svg_path, results,
              "Triangles in memory per layer, analytic cube " + std::to_string(n) + "\xC2\xB3, E0 " +
                  fmt("%.2g", options.simplify.max_error));
    std::printf("plot: %s\n", svg_path.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_tandem_memory: %s\n", e.what());
    return 1;
  }
  return 0;
}
