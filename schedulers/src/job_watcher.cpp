#include "geotandem/schedulers/job_watcher.hpp"

#include <thread>

namespace geotandem::schedulers {

using Clock = std::chrono::steady_clock;

JobWatcher::JobWatcher(Scheduler& scheduler, WatchOptions options) : scheduler_(scheduler), options_(options) {}

std::map<JobId, JobStatus> JobWatcher::statuses(const std::vector<JobId>& ids) {
  bool unseen = false;
  for (const auto& id : ids)
    unseen = unseen || !last_.count(id);
  if (!polled_ || unseen || Clock::now() - last_poll_ >= options_.interval) {
    for (auto& [id, status] : scheduler_.poll(ids))
      last_[id] = status;
    last_poll_ = Clock::now();
    polled_ = true;
    ++polls_;
  }
  std::map<JobId, JobStatus> answer;
  for (const auto& id : ids)
    answer[id] = last_[id];
  return answer;
}

std::map<JobId, JobStatus> JobWatcher::wait_all(const std::vector<JobId>& ids, const CancelToken& cancel,
                                                std::optional<std::chrono::milliseconds> limit) {
  const auto start = Clock::now();
  for (;;) {
    if (cancel.cancelled()) {
      scheduler_.cancel(ids);
      throw Cancelled();
    }
    auto now_statuses = statuses(ids);
    bool done = true;
    for (const auto& [id, status] : now_statuses)
      done = done && is_terminal(status.state);
    if (done) return now_statuses;
    if (limit && Clock::now() - start >= *limit) {
      std::string unfinished;
      for (const auto& [id, status] : now_statuses)
        if (!is_terminal(status.state))
          unfinished += (unfinished.empty() ? "" : ", ") + id + " " + to_string(status.state);
      throw SchedulerError(scheduler_.name(),
                           "jobs still unfinished after " + std::to_string(limit->count()) + " ms: " + unfinished,
                           "check the queue; the jobs were left as they are");
    }
    // Sleep until the next poll is due, in short steps so that a cancel is seen promptly.
    const auto next = last_poll_ + options_.interval;
    while (Clock::now() < next && !cancel.cancelled() && !(limit && Clock::now() - start >= *limit))
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

} // namespace geotandem::schedulers
