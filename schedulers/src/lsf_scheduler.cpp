#include "geotandem/schedulers/lsf_scheduler.hpp"

#include "geotandem/schedulers/lsf_commands.hpp"

namespace geotandem::schedulers {

LsfScheduler::LsfScheduler(SchedulerOptions options) : Scheduler(std::move(options)) {}
LsfScheduler::~LsfScheduler() {
  cancel_all_if_configured();
}

std::vector<JobId> LsfScheduler::do_submit(const LaunchRequest& request) {
  auto argv = lsf::bsub_command(request);
  CommandResult result = run(argv);
  if (!result.ok()) {
    std::string hint;
    if (result.err.find("queue") != std::string::npos)
      hint = "check the queue (execution.resources.queue) against `bqueues`";
    throw command_failed(name(), argv, result, hint);
  }
  auto id = lsf::parse_bsub_output(result.out);
  if (!id)
    throw SchedulerError(name(),
                         "`bsub` did not say 'Job <N> is submitted to queue <Q>.'; it printed: '" + result.out + "'",
                         "is the bsub on PATH LSF's own?");
  return lsf::element_ids(*id, request.array_size);
}

std::vector<JobReport> LsfScheduler::do_poll(const std::vector<JobId>& ids) {
  auto argv = lsf::bjobs_command(ids);
  CommandResult result = run(argv);
  // bjobs exits non-zero when some id is unknown (finished longer than CLEAN_PERIOD ago) and still
  // prints valid lines for the others: only a failure to run it, a hang, or a non-zero exit with
  // nothing about any job is an error.
  auto reports = lsf::parse_bjobs_output(result.out);
  bool only_unknown =
      result.err.find("is not found") != std::string::npos || result.out.find("is not found") != std::string::npos;
  if (!result.spawn_error.empty() || result.timed_out || result.signal != 0 ||
      (result.exit_code != 0 && reports.empty() && !only_unknown))
    throw command_failed(name(), argv, result, "is LSF up? `lsid` and `bhosts` tell");
  return reports;
}

void LsfScheduler::do_cancel(const std::vector<JobId>& ids) {
  auto argv = lsf::bkill_command(ids);
  CommandResult result = run(argv);
  if (result.ok()) return;
  if (result.spawn_error.empty() && !result.timed_out && lsf::bkill_reports_finished(result.err + result.out)) return;
  throw command_failed(name(), argv, result, "is LSF up? `lsid` and `bhosts` tell");
}

} // namespace geotandem::schedulers
