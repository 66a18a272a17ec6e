#include "geotandem/schedulers/replacement_policy.hpp"

#include "geotandem/schedulers/scheduler_error.hpp"

namespace geotandem::schedulers {

std::string describe(const JobStatus& status) {
  std::string text = to_string(status.state);
  if (status.signal)
    text += " (signal " + std::to_string(*status.signal) + ")";
  else if (status.exit_code && status.state != JobState::completed)
    text += " (exit " + std::to_string(*status.exit_code) + ")";
  if (!status.reason.empty()) text += ": " + status.reason;
  if (!status.host.empty()) text += " on " + status.host;
  return text;
}

ReplacementPolicy::ReplacementPolicy(int max_replacements) : limit_(max_replacements) {
  if (max_replacements < 0)
    throw InvalidArgument("replacement limit is " + std::to_string(max_replacements), {}, "use 0 or more");
}

bool ReplacementPolicy::wants_replacement(const JobStatus& status) noexcept {
  switch (status.state) {
  case JobState::vanished:
  case JobState::node_failure:
  case JobState::cancelled:
  case JobState::timed_out: return true;
  case JobState::failed: return status.signal.has_value() && *status.signal != 0;
  default: return false;
  }
}

void ReplacementPolicy::record(const std::string& backend, const JobId& job, const JobStatus& status) {
  if (!wants_replacement(status))
    throw InvalidArgument("job " + job + " is " + describe(status) + ": it is not replaced", {},
                          "only jobs the scheduler lost or killed are replaced");
  if (used_ >= limit_)
    throw SchedulerError(backend,
                         "job " + job + " " + describe(status) + ", and the run has already replaced " +
                             std::to_string(used_) + " lost or killed job(s), its limit",
                         "look at why the scheduler ends the jobs (walltime, memory, node health) or raise "
                         "the replacement limit");
  ++used_;
}

} // namespace geotandem::schedulers
