#pragma once
// The Slurm backend: sbatch to submit, one squeue for the status of all jobs, scancel to cancel.
// No sacct (sites without accounting are common): finished jobs stay visible to squeue for
// MinJobAge seconds (300 by default); a job that disappears before we saw it finish is `vanished`.

#include "geotandem/schedulers/scheduler.hpp"

namespace geotandem::schedulers {

class SlurmScheduler final : public Scheduler {
public:
  explicit SlurmScheduler(SchedulerOptions options = {});
  ~SlurmScheduler() override;
  const char* name() const noexcept override { return "slurm"; }

private:
  std::vector<JobId> do_submit(const LaunchRequest& request) override;
  std::vector<JobReport> do_poll(const std::vector<JobId>& ids) override;
  void do_cancel(const std::vector<JobId>& ids) override;
};

} // namespace geotandem::schedulers
