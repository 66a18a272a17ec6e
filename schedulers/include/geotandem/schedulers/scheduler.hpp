#pragma once
// One interface for every scheduler backend (local, slurm, lsf). The runtime submits worker jobs,
// polls them and cancels them through it; it knows nothing of meshes.
//
// Thread safety: every public member may be called from any thread; calls are serialised.

#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "geotandem/core/log.hpp"
#include "geotandem/schedulers/command_runner.hpp"
#include "geotandem/schedulers/job_state.hpp"
#include "geotandem/schedulers/launch_request.hpp"
#include "geotandem/schedulers/scheduler_error.hpp"

namespace geotandem::schedulers {

struct SchedulerOptions {
  // Runs sbatch/squeue/bsub/...; null means a ProcessCommandRunner.
  std::shared_ptr<CommandRunner> runner;
  // A scheduler command that has not finished by then is killed and reported as hanging.
  std::chrono::milliseconds command_timeout{std::chrono::seconds(60)};
  // Cancel every unfinished job this object submitted when it is destroyed.
  bool cancel_on_destruction = true;
  // Where a failed cancel on destruction is reported (with the ids to cancel by hand); null: stderr.
  geotandem::Logger* logger = nullptr;
};

class Scheduler {
public:
  explicit Scheduler(SchedulerOptions options);
  virtual ~Scheduler() = default;
  Scheduler(const Scheduler&) = delete;
  Scheduler& operator=(const Scheduler&) = delete;

  // "local", "slurm" or "lsf".
  virtual const char* name() const noexcept = 0;

  // Submits the request; one id per array element, in index order. Throws SchedulerError when
  // the scheduler refuses it or its command fails or hangs, InvalidArgument for a bad request.
  std::vector<JobId> submit(const LaunchRequest& request);

  // The status of each id, with ONE scheduler command for all of them. States only move forward
  // (see advance()); a job this object submitted that the scheduler no longer reports before it
  // finished is `vanished`, as is an id this object never submitted. Throws SchedulerError when
  // the status command fails or hangs (the previous statuses stay valid).
  std::map<JobId, JobStatus> poll(const std::vector<JobId>& ids);

  // Asks the scheduler to end these jobs. Idempotent: finished, cancelled or unknown ids are
  // skipped, and cancelling twice is harmless. The jobs are reported `cancelled` once they end.
  void cancel(const std::vector<JobId>& ids);
  // Cancels every job this object submitted that is not known to be finished. Never throws;
  // returns the errors it met, as text (empty when all went well).
  std::string cancel_all() noexcept;

  // Every id submitted through this object, in submission order.
  std::vector<JobId> submitted() const;

protected:
  virtual std::vector<JobId> do_submit(const LaunchRequest& request) = 0;
  // Statuses of the ids the scheduler still knows; ids it does not report are absent.
  virtual std::vector<JobReport> do_poll(const std::vector<JobId>& ids) = 0;
  virtual void do_cancel(const std::vector<JobId>& ids) = 0;

  // Runs a scheduler command through the runner with the configured timeout.
  CommandResult run(const std::vector<std::string>& argv) const;
  // Derived destructors call this first (the base destructor cannot reach do_cancel).
  void cancel_all_if_configured() noexcept;

private:
  SchedulerOptions options_;
  mutable std::recursive_mutex mutex_;
  std::vector<JobId> order_;
  std::map<JobId, JobStatus> known_;
  std::set<JobId> cancel_requested_;
};

// Checks what every backend needs (argv non-empty, array_size >= 1, cpus >= 1); throws
// InvalidArgument naming the field.
void validate(const LaunchRequest& request);

} // namespace geotandem::schedulers
