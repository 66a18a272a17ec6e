#include "geotandem/schedulers/scheduler.hpp"

#include <algorithm>
#include <cstdio>

namespace geotandem::schedulers {

void validate(const LaunchRequest& request) {
  if (request.argv.empty() || request.argv.front().empty())
    throw InvalidArgument("launch request: argv is empty", {}, "give the program to run and its arguments");
  if (request.array_size < 1)
    throw InvalidArgument("launch request: array_size is " + std::to_string(request.array_size), {},
                          "it must be at least 1");
  if (request.resources.cpus < 1)
    throw InvalidArgument("launch request: cpus is " + std::to_string(request.resources.cpus), {},
                          "ask for at least 1 CPU");
  if (request.resources.walltime.count() < 0) throw InvalidArgument("launch request: walltime is negative");
  for (const auto& [key, value] : request.env) {
    if (key.empty() || key.find('=') != std::string::npos)
      throw InvalidArgument("launch request: environment variable name '" + key + "' is not valid");
  }
}

Scheduler::Scheduler(SchedulerOptions options) : options_(std::move(options)) {
  if (!options_.runner) options_.runner = std::make_shared<ProcessCommandRunner>();
}

CommandResult Scheduler::run(const std::vector<std::string>& argv) const {
  return options_.runner->run(argv, options_.command_timeout);
}

std::vector<JobId> Scheduler::submit(const LaunchRequest& request) {
  validate(request);
  std::lock_guard lock(mutex_);
  std::vector<JobId> ids = do_submit(request);
  for (const auto& id : ids) {
    if (known_.emplace(id, JobStatus{}).second) order_.push_back(id);
  }
  return ids;
}

std::map<JobId, JobStatus> Scheduler::poll(const std::vector<JobId>& ids) {
  std::lock_guard lock(mutex_);
  std::vector<JobId> ask;
  for (const auto& id : ids) {
    auto it = known_.find(id);
    if (it != known_.end() && !is_terminal(it->second.state) && std::find(ask.begin(), ask.end(), id) == ask.end())
      ask.push_back(id);
  }
  std::map<JobId, JobStatus> seen;
  if (!ask.empty()) {
    for (auto& observation : do_poll(ask))
      seen[observation.id] = std::move(observation.status);
  }
  std::map<JobId, JobStatus> answer;
  for (const auto& id : ids) {
    auto it = known_.find(id);
    if (it == known_.end()) {
      answer[id] = JobStatus{JobState::vanished, {}, {}, "not submitted through this scheduler object", {}};
      continue;
    }
    JobStatus& status = it->second;
    if (!is_terminal(status.state)) {
      auto found = seen.find(id);
      if (found == seen.end()) {
        JobStatus lost{JobState::vanished, {}, {}, "the scheduler no longer reports this job", status.host};
        status = advance(status, lost);
      } else {
        JobStatus next = found->second;
        // A job we asked to end that ended badly ended because we asked (LSF reports EXIT).
        if (cancel_requested_.count(id) && (next.state == JobState::failed || next.state == JobState::vanished))
          next.state = JobState::cancelled;
        status = advance(status, next);
      }
    }
    answer[id] = status;
  }
  return answer;
}

void Scheduler::cancel(const std::vector<JobId>& ids) {
  std::lock_guard lock(mutex_);
  std::vector<JobId> live;
  for (const auto& id : ids) {
    auto it = known_.find(id);
    if (it == known_.end() || is_terminal(it->second.state)) continue;
    if (std::find(live.begin(), live.end(), id) == live.end()) live.push_back(id);
  }
  if (live.empty()) return;
  do_cancel(live);
  for (const auto& id : live)
    cancel_requested_.insert(id);
}

std::string Scheduler::cancel_all() noexcept {
  try {
    std::lock_guard lock(mutex_);
    std::vector<JobId> live;
    for (const auto& id : order_)
      if (!is_terminal(known_[id].state) && !cancel_requested_.count(id)) live.push_back(id);
    cancel(live);
    return {};
  } catch (const std::exception& error) {
    return error.what();
  } catch (...) {
    return "unknown error while cancelling";
  }
}

void Scheduler::cancel_all_if_configured() noexcept {
  if (!options_.cancel_on_destruction) return;
  std::string failure = cancel_all();
  if (failure.empty()) return;
  std::string ids;
  {
    std::lock_guard lock(mutex_);
    for (const auto& id : order_)
      if (!is_terminal(known_[id].state)) ids += " " + id;
  }
  std::string message = failure + "; these jobs may still be queued or running, cancel them by hand:" + ids;
  try {
    if (options_.logger)
      options_.logger->error(message);
    else
      std::fprintf(stderr, "error: %s\n", message.c_str());
  } catch (...) {
  }
}

std::vector<JobId> Scheduler::submitted() const {
  std::lock_guard lock(mutex_);
  return order_;
}

} // namespace geotandem::schedulers
