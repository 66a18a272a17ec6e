#pragma once
// The local backend: each job (each array element) is a child process of this process, started
// with posix_spawn (never fork: the runtime holds a ZeroMQ context) in its own process group.
// Walltime is enforced at poll time (SIGTERM, then SIGKILL 5 s later); memory, queue and account
// are ignored. Job ids are "local-1", "local-2", ... The child's environment is ours plus the
// request's env, GEOTANDEM_LAUNCH_TOKEN, GEOTANDEM_JOB_ID and GEOTANDEM_ARRAY_INDEX (0-based).

#include <chrono>
#include <map>
#include <sys/types.h>

#include "geotandem/schedulers/scheduler.hpp"

namespace geotandem::schedulers {

class LocalScheduler final : public Scheduler {
public:
  explicit LocalScheduler(SchedulerOptions options = {});
  // Cancels (if configured) and reaps every child: none is left running or a zombie.
  ~LocalScheduler() override;
  const char* name() const noexcept override { return "local"; }

private:
  struct Child {
    pid_t pid = -1;
    bool reaped = false;
    int wait_status = 0;
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
    std::chrono::steady_clock::time_point kill_at = std::chrono::steady_clock::time_point::max();
    bool timed_out = false;
  };
  std::vector<JobId> do_submit(const LaunchRequest& request) override;
  std::vector<JobReport> do_poll(const std::vector<JobId>& ids) override;
  void do_cancel(const std::vector<JobId>& ids) override;
  void reap(Child& child, bool block);

  std::map<JobId, Child> children_;
  long next_id_ = 1;
};

} // namespace geotandem::schedulers
