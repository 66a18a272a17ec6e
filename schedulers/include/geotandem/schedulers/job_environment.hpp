#pragma once
// Inside a job: who am I? Reads the variables each scheduler sets (Slurm's SLURM_*, LSF's LSB_*,
// the local backend's GEOTANDEM_*), so that a worker finds its job id, array index, launch token
// and hosts the same way under every backend.

#include <functional>
#include <string>
#include <vector>

namespace geotandem::schedulers {

struct JobIdentity {
  std::string backend; // "local", "slurm", "lsf", or "" outside any job
  std::string job_id;  // as the scheduler names it: "4711", "4711_2", "4711[3]", "local-5"
  int array_index = 0; // 0-based on every backend (LSF's 1-based LSB_JOBINDEX minus one)
  std::string token;   // GEOTANDEM_LAUNCH_TOKEN
  // Hosts and slots given to the job: LSB_MCPU_HOSTS ("hA 2 hB 1") on LSF, SLURM_JOB_NODELIST (as
  // given, compressed form included) on Slurm, this machine locally.
  std::vector<std::pair<std::string, int>> hosts;
};

using EnvironmentLookup = std::function<const char*(const char*)>;

// From the process environment (std::getenv) or, for tests, any lookup.
JobIdentity job_identity_from_environment(const EnvironmentLookup& lookup = {});

} // namespace geotandem::schedulers
