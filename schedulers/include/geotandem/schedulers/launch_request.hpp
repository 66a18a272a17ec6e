#pragma once
// What to launch: one command, possibly as an array of identical jobs, with its resources.

#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace geotandem::schedulers {

// Per job (per array element). Zero or empty means "the scheduler's default".
struct Resources {
  int cpus = 1;                        // CPUs for the one task (Slurm -c, LSF -n with span[hosts=1])
  std::uint64_t memory_mb = 0;         // MiB (Slurm --mem, LSF -M ...MB)
  std::chrono::seconds walltime{0};    // rounded up to whole minutes where the scheduler wants them
  std::string queue;                   // Slurm partition, LSF queue
  std::string account;                 // Slurm --account, LSF -P project
  std::vector<std::string> extra_args; // passed to sbatch/bsub verbatim, before the command
};

struct LaunchRequest {
  std::vector<std::string> argv;          // the program and its arguments; argv[0] is looked up on PATH
  std::map<std::string, std::string> env; // added to the job's environment (the submitter's is inherited)
  std::string workdir;                    // the job's working directory (empty: the current one)
  // Output files. "{job}" becomes the job id and "{index}" the array index as the scheduler numbers
  // it (0-based for local and Slurm, 1-based for LSF). Empty: the scheduler's default
  // (Slurm: slurm-<id>.out in workdir; LSF: mail or its own default; local: /dev/null).
  std::string stdout_path;
  std::string stderr_path;
  std::string name = "geotandem"; // job name shown by squeue/bjobs
  int array_size = 1;             // >1 submits an array; submit() returns one id per element
  // Issued by the caller and exported to the job as GEOTANDEM_LAUNCH_TOKEN, so that a worker can
  // prove which launch it belongs to (a requeued or duplicated job carries the same token).
  std::string token;
  Resources resources;
};

// The variable that carries LaunchRequest::token into the job.
inline constexpr const char* launch_token_variable = "GEOTANDEM_LAUNCH_TOKEN";

} // namespace geotandem::schedulers
