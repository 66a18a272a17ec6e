#include "geotandem/schedulers/slurm_scheduler.hpp"

#include "geotandem/schedulers/slurm_commands.hpp"

namespace geotandem::schedulers {

SlurmScheduler::SlurmScheduler(SchedulerOptions options) : Scheduler(std::move(options)) {}
SlurmScheduler::~SlurmScheduler() {
  cancel_all_if_configured();
}

std::vector<JobId> SlurmScheduler::do_submit(const LaunchRequest& request) {
  auto argv = slurm::sbatch_command(request);
  CommandResult result = run(argv);
  if (!result.ok()) {
    std::string hint;
    if (result.err.find("partition") != std::string::npos)
      hint = "check the partition (execution.resources.queue) against `sinfo -s`";
    else if (result.err.find("account") != std::string::npos)
      hint = "check the account (execution.resources.account) with your site's administrators";
    throw command_failed(name(), argv, result, hint);
  }
  auto id = slurm::parse_sbatch_output(result.out);
  if (!id)
    throw SchedulerError(name(), "`sbatch --parsable` printed no job id: '" + result.out + "'",
                         "is the sbatch on PATH Slurm's own?");
  return slurm::element_ids(*id, request.array_size);
}

std::vector<JobReport> SlurmScheduler::do_poll(const std::vector<JobId>& ids) {
  auto argv = slurm::squeue_command(slurm::squeue_query_ids(ids));
  CommandResult result = run(argv);
  if (!result.ok() &&
      !(result.spawn_error.empty() && !result.timed_out && slurm::squeue_reports_unknown_ids(result.err)))
    throw command_failed(name(), argv, result, "is slurmctld up? `sinfo` tells");
  auto reports = slurm::match_reports(ids, slurm::parse_squeue_output(result.out));
  // Exit code and signal of jobs that ended badly: squeue has no field for them, so ask scontrol
  // once per such job (the base class never polls a job again once it is terminal).
  for (auto& report : reports) {
    const JobState s = report.status.state;
    if (s == JobState::failed || s == JobState::timed_out) {
      CommandResult detail = run(slurm::scontrol_command(report.id));
      if (detail.ok()) slurm::parse_scontrol_exit(detail.out, report.status);
    }
  }
  return reports;
}

void SlurmScheduler::do_cancel(const std::vector<JobId>& ids) {
  auto argv = slurm::scancel_command(ids);
  CommandResult result = run(argv);
  if (!result.ok()) throw command_failed(name(), argv, result, "is slurmctld up? `sinfo` tells");
}

} // namespace geotandem::schedulers
