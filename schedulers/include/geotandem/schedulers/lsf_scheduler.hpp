#pragma once
// The LSF backend: bsub to submit, one bjobs -o for the status of all jobs, bkill to cancel.
// Never run against a real LSF (none can be installed here); exercised end to end through the
// stand-in bsub/bjobs/bkill in tests/schedulers/lsf-standin/. See schedulers/README.md.

#include "geotandem/schedulers/scheduler.hpp"

namespace geotandem::schedulers {

class LsfScheduler final : public Scheduler {
public:
  explicit LsfScheduler(SchedulerOptions options = {});
  ~LsfScheduler() override;
  const char* name() const noexcept override { return "lsf"; }

private:
  std::vector<JobId> do_submit(const LaunchRequest& request) override;
  std::vector<JobReport> do_poll(const std::vector<JobId>& ids) override;
  void do_cancel(const std::vector<JobId>& ids) override;
};

} // namespace geotandem::schedulers
