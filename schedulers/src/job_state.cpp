#include "geotandem/schedulers/job_state.hpp"

namespace geotandem::schedulers {

const char* to_string(JobState state) noexcept {
  switch (state) {
  case JobState::pending: return "pending";
  case JobState::running: return "running";
  case JobState::completed: return "completed";
  case JobState::failed: return "failed";
  case JobState::cancelled: return "cancelled";
  case JobState::timed_out: return "timed_out";
  case JobState::node_failure: return "node_failure";
  case JobState::vanished: return "vanished";
  }
  return "unknown";
}

bool is_terminal(JobState state) noexcept {
  return state != JobState::pending && state != JobState::running;
}

namespace {
int rank(JobState state) noexcept {
  if (state == JobState::pending) return 0;
  if (state == JobState::running) return 1;
  return 2;
}
void fill_missing(JobStatus& into, const JobStatus& from) {
  if (!into.exit_code) into.exit_code = from.exit_code;
  if (!into.signal) into.signal = from.signal;
  if (into.reason.empty()) into.reason = from.reason;
  if (into.host.empty()) into.host = from.host;
}
} // namespace

JobStatus advance(const JobStatus& previous, const JobStatus& next) {
  // A terminal state is final; running never goes back to pending (a requeue we did not ask for
  // is still the same launch as far as the caller is concerned).
  if (is_terminal(previous.state) || rank(next.state) < rank(previous.state)) {
    JobStatus kept = previous;
    if (kept.state == next.state || !is_terminal(previous.state)) fill_missing(kept, next);
    return kept;
  }
  JobStatus taken = next;
  if (taken.state == previous.state)
    fill_missing(taken, previous);
  else if (taken.host.empty())
    taken.host = previous.host; // where it ran is still true
  return taken;
}

} // namespace geotandem::schedulers
