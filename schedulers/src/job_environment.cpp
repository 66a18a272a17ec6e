#include "geotandem/schedulers/job_environment.hpp"

#include <cstdlib>
#include <sstream>

namespace geotandem::schedulers {

namespace {
std::string text(const EnvironmentLookup& lookup, const char* name) {
  const char* value = lookup(name);
  return value ? std::string(value) : std::string();
}
int number(const std::string& value, int fallback) {
  try {
    return value.empty() ? fallback : std::stoi(value);
  } catch (const std::exception&) {
    return fallback;
  }
}
} // namespace

JobIdentity job_identity_from_environment(const EnvironmentLookup& given) {
  EnvironmentLookup lookup = given ? given : EnvironmentLookup([](const char* name) { return std::getenv(name); });
  JobIdentity identity;
  identity.token = text(lookup, "GEOTANDEM_LAUNCH_TOKEN");
  if (!text(lookup, "GEOTANDEM_JOB_ID").empty()) {
    identity.backend = "local";
    identity.job_id = text(lookup, "GEOTANDEM_JOB_ID");
    identity.array_index = number(text(lookup, "GEOTANDEM_ARRAY_INDEX"), 0);
    identity.hosts = {{"localhost", 1}};
  } else if (!text(lookup, "SLURM_JOB_ID").empty()) {
    identity.backend = "slurm";
    std::string array_job = text(lookup, "SLURM_ARRAY_JOB_ID");
    std::string task = text(lookup, "SLURM_ARRAY_TASK_ID");
    identity.job_id = array_job.empty() || task.empty() ? text(lookup, "SLURM_JOB_ID") : array_job + "_" + task;
    identity.array_index = number(task, 0);
    std::string nodes = text(lookup, "SLURM_JOB_NODELIST");
    if (!nodes.empty()) identity.hosts = {{nodes, number(text(lookup, "SLURM_CPUS_PER_TASK"), 1)}};
  } else if (!text(lookup, "LSB_JOBID").empty()) {
    identity.backend = "lsf";
    int index = number(text(lookup, "LSB_JOBINDEX"), 0); // 0 when the job is not an array
    identity.job_id = text(lookup, "LSB_JOBID") + (index > 0 ? "[" + std::to_string(index) + "]" : "");
    identity.array_index = index > 0 ? index - 1 : 0;
    std::istringstream pairs(text(lookup, "LSB_MCPU_HOSTS"));
    std::string host;
    int slots = 0;
    while (pairs >> host >> slots)
      identity.hosts.emplace_back(host, slots);
    if (identity.hosts.empty()) {
      // LSB_HOSTS lists one word per slot: "hA hA hB".
      std::istringstream words(text(lookup, "LSB_HOSTS"));
      while (words >> host) {
        if (!identity.hosts.empty() && identity.hosts.back().first == host)
          ++identity.hosts.back().second;
        else
          identity.hosts.emplace_back(host, 1);
      }
    }
  }
  return identity;
}

} // namespace geotandem::schedulers
