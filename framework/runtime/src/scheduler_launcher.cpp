// Workers as cluster jobs (scheduler_launcher.hpp).
#include "geotandem/runtime/scheduler_launcher.hpp"

#include <chrono>
#include <set>
#include <utility>

#include "geotandem/core/error.hpp"
#include "geotandem/schedulers/job_watcher.hpp"
#include "geotandem/schedulers/make_scheduler.hpp"
#include "geotandem/schedulers/replacement_policy.hpp"
#include "geotandem/schedulers/scheduler_error.hpp"

namespace geotandem::runtime {

namespace {

namespace sch = geotandem::schedulers;

std::string log_file_of(const std::string& pattern, const std::string& job) {
  if (pattern.empty()) return "the scheduler's default output file";
  std::string path = pattern;
  for (std::size_t at = path.find("{job}"); at != std::string::npos; at = path.find("{job}", at + job.size()))
    path.replace(at, 5, job);
  return path;
}

class SchedulerLauncher final : public Launcher {
public:
  SchedulerLauncher(const SchedulerLaunchOptions& options, Logger& log)
      : options_(options), log_(log), scheduler_(make(options, log)),
        watcher_(*scheduler_, sch::WatchOptions{options.poll_interval}), policy_(options.max_replacements) {}

  ~SchedulerLauncher() override { stop_all(0); }

  void launch(const std::vector<std::string>& argv, const std::string& token) override {
    sch::LaunchRequest request;
    request.argv = argv;
    request.env = options_.env;
    if (options_.walltime.count() > 0) // the worker stops taking tasks near it (walltime.hpp)
      request.env["GEOTANDEM_WALLTIME_SECONDS"] = std::to_string(options_.walltime.count());
    request.workdir = options_.workdir;
    request.stdout_path = options_.log_pattern;
    request.stderr_path = options_.log_pattern;
    request.name = options_.job_name;
    request.token = token;
    request.resources.cpus = options_.cpus;
    request.resources.memory_mb = options_.memory_mb;
    request.resources.walltime = options_.walltime;
    request.resources.queue = options_.queue;
    request.resources.account = options_.account;
    request.resources.extra_args = options_.extra_args;
    const std::vector<sch::JobId> ids = scheduler_->submit(request); // SchedulerError names the command
    for (const sch::JobId& id : ids) {
      jobs_[id] = token;
      open_.insert(id);
      log_.info(std::string(scheduler_->name()) + ": worker " + token + " submitted as job " + id +
                " (log: " + log_file_of(options_.log_pattern, id) + ")");
    }
  }

  // The manager asks this while waiting for workers told FINISHED to leave (the end of a run): it
  // may ask the scheduler directly, at most once a second and 5 times in all, rather than wait for
  // the next 30 s poll.
  std::size_t running() override {
    refresh(true);
    return open_.size();
  }

  std::vector<std::string> ended() override {
    refresh();
    return std::exchange(ended_, {});
  }

  void stop_all(double /*grace_seconds*/) override {
    // The scheduler ends the jobs itself (SIGTERM, then SIGKILL after its own grace period).
    if (open_.empty() || stopped_) return;
    stopped_ = true;
    const std::string errors = scheduler_->cancel_all();
    if (!errors.empty())
      log_.warning(std::string(scheduler_->name()) + ": could not cancel every worker job: " + errors);
    else
      log_.info(std::string(scheduler_->name()) + ": cancelled the worker jobs not yet seen finished (" +
                std::to_string(open_.size()) + ")");
    open_.clear();
  }

private:
  static std::unique_ptr<sch::Scheduler> make(const SchedulerLaunchOptions& options, Logger& log) {
    sch::SchedulerOptions s;
    s.command_timeout = options.command_timeout;
    s.cancel_on_destruction = true;
    s.logger = &log;
    return sch::make_scheduler(options.backend, s);
  }

  // Moves the jobs the scheduler reports finished from open_ to ended_, applying the replacement
  // policy. A poll that fails is logged and retried later: heartbeats still tell who is alive.
  void refresh(bool eager = false) {
    if (open_.empty() || stopped_) return;
    std::map<sch::JobId, sch::JobStatus> statuses;
    const auto now = std::chrono::steady_clock::now();
    eager = eager && eager_polls_ < 5 && now - last_eager_ >= std::chrono::seconds(1);
    try {
      if (eager) {
        ++eager_polls_;
        last_eager_ = now;
        statuses = scheduler_->poll({open_.begin(), open_.end()});
      } else {
        statuses = watcher_.statuses({open_.begin(), open_.end()});
      }
    } catch (const sch::SchedulerError& e) {
      log_.warning(std::string("cannot ask the scheduler about the worker jobs (will retry): ") + e.what());
      return;
    }
    for (auto [id, status] : statuses) {
      if (!sch::is_terminal(status.state) || !open_.count(id)) continue;
      // LSF reports a killed job as EXIT with the shell's 128 + signal (130 after bkill's SIGTERM
      // reached a worker that then exited): killed, not failed by itself.
      if (status.state == sch::JobState::failed && !status.signal && status.exit_code && *status.exit_code > 128 &&
          *status.exit_code < 160)
        status.signal = *status.exit_code - 128;
      open_.erase(id);
      const std::string& token = jobs_.at(id);
      if (sch::ReplacementPolicy::wants_replacement(status)) {
        log_.warning(std::string(scheduler_->name()) + ": worker " + token + " (job " + id + ") " +
                     sch::describe(status) + "; it will be replaced");
        policy_.record(scheduler_->name(), id, status); // throws past the limit
      } else if (status.state == sch::JobState::failed) {
        throw sch::SchedulerError(scheduler_->name(), "worker " + token + " (job " + id + ") " + sch::describe(status),
                                  "see its log in " + log_file_of(options_.log_pattern, id));
      }
      ended_.push_back(token);
    }
  }

  SchedulerLaunchOptions options_;
  Logger& log_;
  std::unique_ptr<sch::Scheduler> scheduler_;
  sch::JobWatcher watcher_;
  sch::ReplacementPolicy policy_;
  std::map<sch::JobId, std::string> jobs_; // job id -> launch token
  std::set<sch::JobId> open_;              // submitted, not yet seen in a terminal state
  std::vector<std::string> ended_;
  bool stopped_ = false;
  int eager_polls_ = 0;
  std::chrono::steady_clock::time_point last_eager_{};
};

} // namespace

std::unique_ptr<Launcher> make_scheduler_launcher(const SchedulerLaunchOptions& options, Logger& log) {
  return std::make_unique<SchedulerLauncher>(options, log);
}

} // namespace geotandem::runtime
