// Scheduler latency: for each job, the time from submit() to the scheduler reporting it running,
// and to the first line of its output appearing in its output file. Prints figures; not a test.
//
// Usage: bench_scheduler_latency [--backend local|slurm|lsf] [--jobs N] [--dir DIR]
//   slurm needs SLURM_CONF (scripts/slurm-bench.sh starts a private cluster and runs this).
// Polls every 50 ms, far more often than the runtime would (30 s), to measure latency itself.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <string>
#include <thread>
#include <vector>

#include "geotandem/schedulers/make_scheduler.hpp"

using namespace geotandem::schedulers;
using Clock = std::chrono::steady_clock;

namespace {
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

bool has_line(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  return static_cast<bool>(std::getline(in, line)) && !in.eof();
}

void print_row(const char* what, std::vector<double> values) {
  std::sort(values.begin(), values.end());
  double mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
  std::printf("%-28s min %7.3f s  median %7.3f s  max %7.3f s  mean %7.3f s\n", what, values.front(),
              values[values.size() / 2], values.back(), mean);
}
} // namespace

int main(int argc, char** argv) {
  std::string backend = "local";
  int jobs = 5;
  std::filesystem::path dir = std::filesystem::temp_directory_path() / "geotandem-bench-scheduler";
  for (int i = 1; i + 1 < argc; i += 2) {
    std::string key = argv[i];
    if (key == "--backend")
      backend = argv[i + 1];
    else if (key == "--jobs")
      jobs = std::max(1, std::atoi(argv[i + 1]));
    else if (key == "--dir")
      dir = argv[i + 1];
    else {
      std::fprintf(stderr, "unknown option %s\nusage: %s [--backend local|slurm|lsf] [--jobs N] [--dir DIR]\n",
                   key.c_str(), argv[0]);
      return 2;
    }
  }
  try {
    std::filesystem::create_directories(dir);
    auto scheduler = make_scheduler(backend);
    std::vector<double> to_running, to_output, submit_call;
    for (int j = 0; j < jobs; ++j) {
      auto out = dir / ("job-" + std::to_string(j) + ".out");
      std::filesystem::remove(out);
      LaunchRequest request;
      request.argv = {"/bin/sh", "-c", "echo first line; sleep 2"};
      request.workdir = dir.string();
      request.stdout_path = out.string();
      request.name = "gt-bench";
      const auto start = Clock::now();
      auto ids = scheduler->submit(request);
      submit_call.push_back(seconds_since(start));
      bool running = false, output = false;
      while (!(running && output) && seconds_since(start) < 300) {
        if (!running) {
          auto state = scheduler->poll(ids)[ids[0]].state;
          if (state != JobState::pending) {
            running = true;
            to_running.push_back(seconds_since(start));
          }
        }
        if (!output && has_line(out)) {
          output = true;
          to_output.push_back(seconds_since(start));
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
      if (!running || !output) {
        std::fprintf(stderr, "job %d did not start within 300 s\n", j);
        return 1;
      }
      // Let it finish so the next job starts on an idle node.
      while (!is_terminal(scheduler->poll(ids)[ids[0]].state))
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    std::printf("backend %s, %d jobs, one after another (poll every 50 ms)\n", backend.c_str(), jobs);
    print_row("submit() call", submit_call);
    print_row("submit -> running", to_running);
    print_row("submit -> first output line", to_output);
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "bench_scheduler_latency: %s\n", error.what());
    return 1;
  }
}
