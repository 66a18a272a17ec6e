#include "geotandem/schedulers/local_scheduler.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <thread>

#include "job_command.hpp"
#include "posix_spawn_util.hpp"

extern char** environ;

namespace geotandem::schedulers {

namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kill_grace = std::chrono::seconds(5);

std::string expand(const std::string& path, const std::string& id, int index) {
  if (path.empty()) return "/dev/null";
  // '%' has no meaning here: keep it as it is.
  return output_pattern(path, id, std::to_string(index), "%");
}

std::vector<std::string> child_environment(const LaunchRequest& request, const std::string& id, int index) {
  std::map<std::string, std::string> overlay = request.env;
  if (!request.token.empty()) overlay[launch_token_variable] = request.token;
  overlay["GEOTANDEM_JOB_ID"] = id;
  overlay["GEOTANDEM_ARRAY_INDEX"] = std::to_string(index);
  std::vector<std::string> env;
  for (char** entry = environ; *entry != nullptr; ++entry) {
    std::string text(*entry);
    if (!overlay.count(text.substr(0, text.find('=')))) env.push_back(std::move(text));
  }
  for (const auto& [key, value] : overlay)
    env.push_back(key + "=" + value);
  return env;
}

} // namespace

LocalScheduler::LocalScheduler(SchedulerOptions options) : Scheduler(std::move(options)) {}

LocalScheduler::~LocalScheduler() {
  cancel_all_if_configured();
  // Reap everything: children we cancelled get the grace period, then SIGKILL.
  const auto give_up = Clock::now() + kill_grace;
  for (auto& [id, child] : children_) {
    while (!child.reaped && Clock::now() < give_up) {
      reap(child, false);
      if (!child.reaped) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (!child.reaped) {
      ::kill(-child.pid, SIGKILL);
      reap(child, true);
    }
  }
}

void LocalScheduler::reap(Child& child, bool block) {
  if (child.reaped) return;
  int status = 0;
  pid_t done;
  do {
    done = ::waitpid(child.pid, &status, block ? 0 : WNOHANG);
  } while (done < 0 && errno == EINTR);
  if (done == child.pid) {
    child.reaped = true;
    child.wait_status = status;
  } else if (done < 0) {
    child.reaped = true; // ECHILD: someone else reaped it; its status is lost
    child.wait_status = -1;
  }
}

std::vector<JobId> LocalScheduler::do_submit(const LaunchRequest& request) {
  if (!request.workdir.empty() && !std::filesystem::is_directory(request.workdir))
    throw InvalidArgument("local: working directory '" + request.workdir + "' does not exist", {},
                          "create it or give an existing one");
  std::vector<JobId> ids;
  for (int index = 0; index < request.array_size; ++index) {
    JobId id = "local-" + std::to_string(next_id_++);
    SpawnActions actions;
    if (!request.workdir.empty()) actions.change_directory(request.workdir);
    actions.open_dev_null(STDIN_FILENO);
    actions.open_for_writing(STDOUT_FILENO, expand(request.stdout_path, id, index));
    if (request.stderr_path.empty() && !request.stdout_path.empty())
      actions.dup_to(STDOUT_FILENO, STDERR_FILENO);
    else
      actions.open_for_writing(STDERR_FILENO, expand(request.stderr_path, id, index));
    SpawnAttributes attributes(/*own_process_group=*/true);
    std::vector<std::string> env = child_environment(request, id, index);
    CArgv cargv(request.argv), cenv(env);
    pid_t pid = -1;
    int rc = ::posix_spawnp(&pid, request.argv[0].c_str(), actions.get(), attributes.get(), cargv.data(), cenv.data());
    if (rc != 0) {
      std::string why =
          rc == ENOENT ? "not found on PATH, or an output file's directory does not exist" : std::strerror(rc);
      // Earlier elements of this array are already running: they stay ours, cancel_all ends them.
      throw SchedulerError(name(), "cannot start `" + describe_command(request.argv) + "`: " + why,
                           "check the program path and the output file paths");
    }
    Child child;
    child.pid = pid;
    if (request.resources.walltime.count() > 0) child.deadline = Clock::now() + request.resources.walltime;
    children_.emplace(id, child);
    ids.push_back(id);
  }
  return ids;
}

std::vector<JobReport> LocalScheduler::do_poll(const std::vector<JobId>& ids) {
  std::vector<JobReport> reports;
  const auto now = Clock::now();
  for (const auto& id : ids) {
    auto it = children_.find(id);
    if (it == children_.end()) continue;
    Child& child = it->second;
    reap(child, false);
    JobReport report{id, {}};
    report.status.host = "localhost";
    if (!child.reaped) {
      if (now >= child.deadline && !child.timed_out) {
        child.timed_out = true;
        child.kill_at = now + kill_grace;
        ::kill(-child.pid, SIGTERM);
      } else if (now >= child.kill_at) {
        ::kill(-child.pid, SIGKILL);
      }
      report.status.state = JobState::running;
    } else if (child.wait_status == -1) {
      report.status.state = JobState::vanished;
      report.status.reason = "its exit status was collected by someone else";
    } else if (WIFEXITED(child.wait_status)) {
      report.status.exit_code = WEXITSTATUS(child.wait_status);
      report.status.state = report.status.exit_code == 0 ? JobState::completed : JobState::failed;
    } else if (WIFSIGNALED(child.wait_status)) {
      report.status.signal = WTERMSIG(child.wait_status);
      report.status.state = JobState::failed;
    }
    if (child.timed_out && child.reaped) {
      report.status.state = JobState::timed_out;
      report.status.reason = "walltime reached";
    }
    reports.push_back(std::move(report));
  }
  return reports;
}

void LocalScheduler::do_cancel(const std::vector<JobId>& ids) {
  const auto now = Clock::now();
  for (const auto& id : ids) {
    auto it = children_.find(id);
    if (it == children_.end() || it->second.reaped) continue;
    ::kill(-it->second.pid, SIGTERM);
    it->second.kill_at = std::min(it->second.kill_at, now + kill_grace);
  }
}

} // namespace geotandem::schedulers
