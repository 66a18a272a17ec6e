#pragma once
// The life of a scheduler job as every backend reports it. States only move forward: pending ->
// running -> one terminal state; a terminal state never changes again.

#include <optional>
#include <string>

namespace geotandem::schedulers {

// A job id as the scheduler prints it: "4711" (Slurm), "4711_3" (Slurm array element),
// "4711[3]" (LSF array element), "local-12" (local).
using JobId = std::string;

enum class JobState {
  pending,      // queued, held or requeued, not started
  running,      // started (includes suspended and completing)
  completed,    // finished with exit code 0
  failed,       // finished with a non-zero exit code or a signal
  cancelled,    // cancelled by us (or an administrator) or preempted
  timed_out,    // killed at its walltime
  node_failure, // its node died or is unreachable
  vanished,     // the scheduler no longer knows a job that had not finished (lost)
};

// "pending", "running", ..., "node_failure", "vanished".
const char* to_string(JobState state) noexcept;
bool is_terminal(JobState state) noexcept;

// What is known of one job. Fields the backend cannot know stay empty.
struct JobStatus {
  JobState state = JobState::pending;
  std::optional<int> exit_code; // the job's exit status, when it exited
  std::optional<int> signal;    // the signal that ended it, when one did
  std::string reason;           // the scheduler's reason text (pending reason, failure reason)
  std::string host;             // where it runs or ran
};

// One job as a scheduler's status command reported it (before the forward-only rule).
struct JobReport {
  JobId id;
  JobStatus status;
};

// The forward-only rule: `next` replaces `previous` only if it is a later state; a terminal state
// is kept forever. Details (exit code, host, reason) of an accepted observation are kept; a
// rejected observation may still fill in details the previous one lacked.
JobStatus advance(const JobStatus& previous, const JobStatus& next);

} // namespace geotandem::schedulers
