// The Slurm backend against a real Slurm: slurmctld and slurmd started by
// scripts/slurm-test-cluster.sh (the ctest fixture `slurm_cluster` does it; SLURM_CONF comes from
// the environment, as on a site's cluster). Label: slurm.
#include <gtest/gtest.h>

#include <sstream>

#include "backend_checks.hpp"
#include "geotandem/schedulers/replacement_policy.hpp"
#include "geotandem/schedulers/slurm_scheduler.hpp"
#include "scratch.hpp"
#include "test_paths.hpp"

using namespace geotandem::schedulers;
using namespace geotandem::testing;
using namespace std::chrono_literals;

namespace {
class Slurm : public ::testing::Test {
protected:
  ScratchDir dir;
  void SetUp() override {
    const char* conf = std::getenv("SLURM_CONF");
    ASSERT_TRUE(conf && std::filesystem::exists(conf))
        << "SLURM_CONF is not set or missing: run through ctest (fixture slurm_cluster) or start "
           "scripts/slurm-test-cluster.sh start DIR and export SLURM_CONF=DIR/slurm.conf";
  }
};
} // namespace

TEST_F(Slurm, JobCompletesWithEnvironmentAndOutput) {
  SlurmScheduler scheduler;
  check_job_completes_with_env_and_output(scheduler, dir.path());
}

TEST_F(Slurm, JobFailsWithExitCode) {
  SlurmScheduler scheduler;
  check_job_fails_with_exit_code(scheduler, dir.path());
}

TEST_F(Slurm, ScancelMidRunIsCancelled) {
  SlurmScheduler scheduler;
  check_cancel_mid_run(scheduler, dir.path());
}

TEST_F(Slurm, ScancelBySomeoneElseIsCancelledAndReplaceable) {
  SlurmScheduler scheduler;
  auto ids = scheduler.submit(shell_job(dir.path(), "exec sleep 600"));
  JobWatcher watcher(scheduler, quick_watch());
  ASSERT_TRUE(eventually([&] { return watcher.statuses(ids)[ids[0]].state == JobState::running; }, job_bound));
  ProcessCommandRunner runner; // an administrator's scancel, not ours
  ASSERT_TRUE(runner.run({"scancel", ids[0]}, 60s).ok());
  auto status = watcher.wait_all(ids, {}, job_bound)[ids[0]];
  EXPECT_EQ(status.state, JobState::cancelled);
  EXPECT_TRUE(ReplacementPolicy::wants_replacement(status));
}

TEST_F(Slurm, WalltimeEndsTheJobAsTimedOut) {
  // Slurm's smallest walltime is a minute, enforced up to ~30 s late: this test takes 60-100 s.
  SlurmScheduler scheduler;
  auto r = shell_job(dir.path(), "exec sleep 600");
  r.resources.walltime = 1s; // rounded up by Slurm to one minute
  auto ids = scheduler.submit(r);
  auto status = JobWatcher(scheduler, {std::chrono::seconds(2)}).wait_all(ids, {}, std::chrono::seconds(400))[ids[0]];
  EXPECT_EQ(status.state, JobState::timed_out) << status.reason;
  EXPECT_TRUE(ReplacementPolicy::wants_replacement(status));
}

TEST_F(Slurm, Array) {
  SlurmScheduler scheduler;
  check_array(scheduler, dir.path());
}

TEST_F(Slurm, PollManyInOneCallAndUnknown) {
  SlurmScheduler scheduler;
  check_poll_many_and_unknown(scheduler, dir.path());
}

TEST_F(Slurm, OneSqueuePerPollWhateverTheNumberOfJobs) {
  auto runner = std::make_shared<LoggingRunner>();
  SchedulerOptions options;
  options.runner = runner;
  SlurmScheduler scheduler(options);
  auto r = shell_job(dir.path(), "sleep 1");
  r.array_size = 5;
  auto ids = scheduler.submit(r);
  auto single = scheduler.submit(shell_job(dir.path(), "sleep 1"));
  ids.insert(ids.end(), single.begin(), single.end());
  ASSERT_EQ(ids.size(), 6u);
  for (int poll = 1; poll <= 3; ++poll) {
    auto statuses = scheduler.poll(ids);
    ASSERT_EQ(statuses.size(), 6u);
    EXPECT_EQ(runner->count("squeue"), static_cast<std::size_t>(poll));
  }
  auto statuses = JobWatcher(scheduler, quick_watch()).wait_all(ids, {}, job_bound);
  for (const auto& id : ids)
    EXPECT_EQ(statuses[id].state, JobState::completed) << id;
  EXPECT_EQ(runner->count("scontrol"), 0u) << "scontrol is asked only about jobs that failed";
  EXPECT_EQ(runner->count("sbatch"), 2u);
}

TEST_F(Slurm, CancelOfUnknownOrFinishedIsHarmless) {
  SlurmScheduler scheduler;
  auto ids = scheduler.submit(shell_job(dir.path(), "true"));
  JobWatcher(scheduler, quick_watch()).wait_all(ids, {}, job_bound);
  EXPECT_NO_THROW(scheduler.cancel(ids));
  EXPECT_NO_THROW(scheduler.cancel({"424242"}));
  EXPECT_EQ(scheduler.poll(ids)[ids[0]].state, JobState::completed);
}

TEST_F(Slurm, DestructionCancelsUnfinishedJobs) {
  std::vector<JobId> ids;
  {
    SlurmScheduler scheduler;
    auto r = shell_job(dir.path(), "exec sleep 600");
    r.array_size = 2;
    ids = scheduler.submit(r);
  }
  // Asked directly (not through a Scheduler object): every record of the array is cancelled.
  const std::string base = ids[0].substr(0, ids[0].find('_'));
  ProcessCommandRunner runner;
  std::string last;
  ASSERT_TRUE(eventually([&] {
    auto result = runner.run({"squeue", "-h", "-t", "all", "-r", "-j", base, "-o", "%T"}, 60s);
    last = result.out;
    if (!result.ok() || result.out.empty()) return false;
    std::istringstream lines(result.out);
    std::string line;
    while (std::getline(lines, line))
      if (line != "CANCELLED") return false;
    return true;
  })) << last;
}

TEST_F(Slurm, NoSuchPartitionIsAClearError) {
  SlurmScheduler scheduler;
  auto r = shell_job(dir.path(), "true");
  r.resources.queue = "nosuch";
  const auto start = std::chrono::steady_clock::now();
  try {
    scheduler.submit(r);
    FAIL();
  } catch (const SchedulerError& error) {
    std::string what = error.what();
    EXPECT_EQ(what.rfind("slurm: `sbatch ", 0), 0u) << what;
    EXPECT_NE(what.find("-p nosuch"), std::string::npos) << what;
    EXPECT_NE(what.find("invalid partition"), std::string::npos) << what;
    EXPECT_NE(what.find("sinfo"), std::string::npos) << what;
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, 60s);
  EXPECT_TRUE(scheduler.submitted().empty());
}

TEST_F(Slurm, ImpossibleRequestIsRefusedNotLeftPending) {
  SlurmScheduler scheduler;
  auto r = shell_job(dir.path(), "true");
  r.resources.cpus = 4096; // EnforcePartLimits=ALL in the test cluster's configuration
  EXPECT_THROW(scheduler.submit(r), SchedulerError);
}

TEST_F(Slurm, SbatchMissingFromPathIsAClearError) {
  EnvGuard empty_path("PATH", dir.path().string());
  SlurmScheduler scheduler;
  try {
    scheduler.submit(shell_job(dir.path(), "true"));
    FAIL();
  } catch (const SchedulerError& error) {
    std::string what = error.what();
    EXPECT_NE(what.find("slurm: `sbatch "), std::string::npos) << what;
    EXPECT_NE(what.find("'sbatch' not found on PATH"), std::string::npos) << what;
  }
}

TEST_F(Slurm, HangingSbatchIsAClearErrorWithinABoundedTime) {
  EnvGuard hang_path("PATH", path_with(test_paths::hang_simulator()));
  SchedulerOptions options;
  // Long enough for the simulator to have printed its line even on a loaded CI machine.
  options.command_timeout = 5s;
  SlurmScheduler scheduler(options);
  const auto start = std::chrono::steady_clock::now();
  try {
    scheduler.submit(shell_job(dir.path(), "true"));
    FAIL();
  } catch (const SchedulerError& error) {
    std::string what = error.what();
    EXPECT_NE(what.find("slurm: `sbatch "), std::string::npos) << what;
    EXPECT_NE(what.find("hung"), std::string::npos) << what;
    EXPECT_NE(what.find("hang simulator"), std::string::npos) << "what it printed is kept: " << what;
  }
  const auto took = std::chrono::steady_clock::now() - start;
  EXPECT_GE(took, 5s);
  EXPECT_LT(took, 60s);
}
