#pragma once
// Polls a scheduler no more often than an interval (30 s by default: liveness comes from the
// workers' heartbeats, the scheduler is only asked what happened to jobs), and waits for jobs
// with a cancel token: on cancel (Ctrl-C) the jobs are cancelled before Cancelled is thrown.

#include <chrono>
#include <map>
#include <optional>
#include <vector>

#include "geotandem/core/cancel.hpp"
#include "geotandem/schedulers/scheduler.hpp"

namespace geotandem::schedulers {

struct WatchOptions {
  // Minimum time between two status commands. Keep it at 30 s or more on a shared cluster: a
  // controller polled by many users every second becomes everyone's problem. Tests shorten it.
  std::chrono::milliseconds interval{std::chrono::seconds(30)};
};

class JobWatcher {
public:
  explicit JobWatcher(Scheduler& scheduler, WatchOptions options = {});

  // The statuses of ids: asks the scheduler (one command) if the interval has passed since the
  // last time or an id was never asked about; otherwise answers from the last poll.
  std::map<JobId, JobStatus> statuses(const std::vector<JobId>& ids);

  // Waits until every id is in a terminal state and returns their statuses. On cancel, cancels
  // the ids still unfinished and throws geotandem::Cancelled. Past `limit` (if given) throws
  // SchedulerError naming the unfinished jobs and their states (the jobs are left alone).
  std::map<JobId, JobStatus> wait_all(const std::vector<JobId>& ids, const CancelToken& cancel,
                                      std::optional<std::chrono::milliseconds> limit = std::nullopt);

  // How many status commands this watcher has run.
  long polls() const noexcept { return polls_; }

private:
  Scheduler& scheduler_;
  WatchOptions options_;
  std::map<JobId, JobStatus> last_;
  std::chrono::steady_clock::time_point last_poll_{};
  bool polled_ = false;
  long polls_ = 0;
};

} // namespace geotandem::schedulers
