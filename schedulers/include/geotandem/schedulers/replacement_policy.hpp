#pragma once
// Which ended jobs the runtime replaces, and how many times. A job the scheduler lost or killed
// (vanished, node failure, cancelled by someone else, timed out, killed by a signal) is replaced up
// to a limit; a job that exited with an error code is not (a worker that fails by itself would
// fail again), nor one that completed. Past the limit: a clear error.
//
// The runtime does not ask about jobs it cancelled itself.

#include <string>

#include "geotandem/schedulers/job_state.hpp"

namespace geotandem::schedulers {

class ReplacementPolicy {
public:
  // max_replacements >= 0: how many replacements a whole run may make.
  explicit ReplacementPolicy(int max_replacements = 3);

  // True for an ended job that should be replaced (see above); false for a job still running.
  static bool wants_replacement(const JobStatus& status) noexcept;

  // Records one replacement of `job` (call before submitting its replacement). Throws
  // SchedulerError past the limit, naming the job, what happened to it, and the limit; throws
  // InvalidArgument for a job that wants_replacement() refuses.
  void record(const std::string& backend, const JobId& job, const JobStatus& status);

  int used() const noexcept { return used_; }
  int limit() const noexcept { return limit_; }

private:
  int limit_;
  int used_ = 0;
};

// "failed (exit 3)", "failed (signal 9)", "vanished: the scheduler no longer reports this job".
std::string describe(const JobStatus& status);

} // namespace geotandem::schedulers
