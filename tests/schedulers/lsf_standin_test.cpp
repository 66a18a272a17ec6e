// The LSF backend end to end through the STAND-IN bsub/bjobs/bkill of lsf-standin/ (no real LSF
// exists here): jobs really run as local processes and the stand-ins print LSF's formats.
#include <gtest/gtest.h>

#include <signal.h>

#include "backend_checks.hpp"
#include "geotandem/schedulers/lsf_scheduler.hpp"
#include "scratch.hpp"
#include "test_paths.hpp"

using namespace geotandem::schedulers;
using namespace geotandem::testing;

namespace {
class LsfStandin : public ::testing::Test {
protected:
  ScratchDir dir;
  EnvGuard path{"PATH", path_with(test_paths::lsf_standin())};
  EnvGuard state{"LSF_STANDIN_DIR", dir.file("lsf-state")};
  std::filesystem::path jobs() const { return dir.path() / "work"; }
  void SetUp() override { std::filesystem::create_directories(jobs()); }
};
} // namespace

TEST_F(LsfStandin, JobCompletesWithEnvironmentAndOutput) {
  LsfScheduler scheduler;
  check_job_completes_with_env_and_output(scheduler, jobs());
}

TEST_F(LsfStandin, JobFailsWithExitCode) {
  LsfScheduler scheduler;
  check_job_fails_with_exit_code(scheduler, jobs());
}

TEST_F(LsfStandin, CancelMidRun) {
  LsfScheduler scheduler;
  check_cancel_mid_run(scheduler, jobs());
}

TEST_F(LsfStandin, Array) {
  LsfScheduler scheduler;
  check_array(scheduler, jobs());
}

TEST_F(LsfStandin, PollManyAndUnknown) {
  LsfScheduler scheduler;
  check_poll_many_and_unknown(scheduler, jobs());
}

TEST_F(LsfStandin, JobSeesLsbVariablesAndSlots) {
  LsfScheduler scheduler;
  auto r = shell_job(jobs(), "echo \"$LSB_JOBID|$LSB_JOBINDEX|$LSB_MCPU_HOSTS\"");
  r.array_size = 2;
  r.resources.cpus = 2;
  r.stdout_path = (jobs() / "lsb-{index}.out").string();
  auto ids = scheduler.submit(r);
  auto statuses = JobWatcher(scheduler, quick_watch()).wait_all(ids, {}, job_bound);
  const std::string base = ids[0].substr(0, ids[0].find('['));
  for (int index = 1; index <= 2; ++index) {
    std::string text = read_text(jobs() / ("lsb-" + std::to_string(index) + ".out"));
    EXPECT_EQ(text.substr(0, text.find('|', text.find('|') + 1)), base + "|" + std::to_string(index)) << text;
    EXPECT_NE(text.find(" 2\n"), std::string::npos) << "two slots on one host: " << text;
  }
  EXPECT_EQ(statuses[ids[1]].host.rfind("2*", 0), 0u) << statuses[ids[1]].host;
}

TEST_F(LsfStandin, LostJobIsVanished) {
  LsfScheduler scheduler;
  auto ids = scheduler.submit(shell_job(jobs(), "exec sleep 600"));
  JobWatcher watcher(scheduler, quick_watch());
  ASSERT_TRUE(eventually([&] { return watcher.statuses(ids)[ids[0]].state == JobState::running; }));
  // LSF forgets the job (the stand-in's record of it is removed): the job is lost.
  std::string pid = read_text(dir.path() / "lsf-state" / "jobs" / ids[0] / "pid");
  std::filesystem::remove_all(dir.path() / "lsf-state" / "jobs" / ids[0]);
  auto status = watcher.wait_all(ids, {}, job_bound)[ids[0]];
  EXPECT_EQ(status.state, JobState::vanished);
  EXPECT_FALSE(status.reason.empty());
  ::kill(-std::stoi(pid), SIGKILL);
}

TEST_F(LsfStandin, NoSuchQueueIsAClearError) {
  LsfScheduler scheduler;
  auto r = shell_job(jobs(), "true");
  r.resources.queue = "nosuch";
  try {
    scheduler.submit(r);
    FAIL();
  } catch (const SchedulerError& error) {
    std::string what = error.what();
    EXPECT_EQ(what.rfind("lsf: `bsub ", 0), 0u) << what;
    EXPECT_NE(what.find("nosuch: No such queue"), std::string::npos) << what;
    EXPECT_NE(what.find("bqueues"), std::string::npos) << what;
  }
}

TEST_F(LsfStandin, BsubMissingFromPathIsAClearError) {
  EnvGuard empty_path("PATH", dir.path().string());
  LsfScheduler scheduler;
  try {
    scheduler.submit(shell_job(jobs(), "true"));
    FAIL();
  } catch (const SchedulerError& error) {
    EXPECT_NE(std::string(error.what()).find("'bsub' not found on PATH"), std::string::npos) << error.what();
  }
}

TEST_F(LsfStandin, DestructionCancelsUnfinishedJobs) {
  std::vector<JobId> ids;
  {
    LsfScheduler scheduler;
    auto r = shell_job(jobs(), "exec sleep 600");
    r.array_size = 2;
    ids = scheduler.submit(r);
    JobWatcher watcher(scheduler, quick_watch());
    ASSERT_TRUE(eventually([&] {
      auto s = watcher.statuses(ids);
      return s[ids[0]].state == JobState::running && s[ids[1]].state == JobState::running;
    }));
  }
  for (const auto& id : ids) {
    ASSERT_TRUE(eventually([&] { return read_text(dir.path() / "lsf-state" / "jobs" / id / "stat") == "EXIT\n"; }))
        << id;
  }
}

TEST_F(LsfStandin, HangingBsubIsAClearErrorWithinABoundedTime) {
  EnvGuard hang_path("PATH", path_with(test_paths::hang_simulator()));
  SchedulerOptions options;
  options.command_timeout = std::chrono::seconds(5);
  LsfScheduler scheduler(options);
  const auto start = std::chrono::steady_clock::now();
  try {
    scheduler.submit(shell_job(jobs(), "true"));
    FAIL();
  } catch (const SchedulerError& error) {
    std::string what = error.what();
    EXPECT_NE(what.find("lsf: `bsub "), std::string::npos) << what;
    EXPECT_NE(what.find("hung"), std::string::npos) << what;
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(60));
}
