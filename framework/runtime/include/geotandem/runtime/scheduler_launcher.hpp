#pragma once
// Workers as cluster jobs: a Launcher over the schedulers library (local, slurm, lsf). Each launch
// submits one job running the worker's command line, with the launch token, the environment and
// the resources asked for; running() and ended() come from the scheduler's job states, polled at
// most every `poll_interval` (liveness itself comes from the workers' heartbeats); stop_all()
// cancels every job still unfinished. Jobs the scheduler lost or killed are counted against
// `max_replacements` (the manager starts the replacements); past it, and for a job that failed by
// itself before its worker connected, ended() throws an error naming the backend, the job and its
// log file. The schedulers' types stay out of this header: the runtime links them privately.
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "geotandem/core/log.hpp"
#include "geotandem/runtime/launcher.hpp"

namespace geotandem::runtime {

struct SchedulerLaunchOptions {
  std::string backend = "slurm"; // local, slurm or lsf
  int cpus = 1;                  // per worker
  std::uint64_t memory_mb = 0;   // per worker; 0: the scheduler's default
  std::chrono::seconds walltime{0};
  std::string queue; // Slurm partition, LSF queue
  std::string account;
  std::vector<std::string> extra_args;    // to sbatch/bsub verbatim
  std::map<std::string, std::string> env; // added to each job's environment
  std::string workdir;                    // the jobs' working directory (empty: the current one)
  // Where each job's stdout and stderr go; "{job}" becomes the job id. Empty: the scheduler's default.
  std::string log_pattern;
  std::string job_name = "geotandem-worker";
  std::chrono::milliseconds poll_interval{std::chrono::seconds(30)};
  std::chrono::milliseconds command_timeout{std::chrono::seconds(60)};
  int max_replacements = 3;
};

// Throws InvalidArgument for an unknown backend. `log` must outlive the launcher.
std::unique_ptr<Launcher> make_scheduler_launcher(const SchedulerLaunchOptions& options, Logger& log);

} // namespace geotandem::runtime
