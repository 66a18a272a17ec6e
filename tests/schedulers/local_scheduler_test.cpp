// The local backend: child processes started with posix_spawn, for real.
#include <gtest/gtest.h>

#include <fstream>
#include <signal.h>

#include "backend_checks.hpp"
#include "geotandem/schedulers/local_scheduler.hpp"
#include "geotandem/schedulers/make_scheduler.hpp"
#include "scratch.hpp"

using namespace geotandem::schedulers;
using namespace geotandem::testing;
using namespace std::chrono_literals;

namespace {
// True while pid is a live process (not a zombie): /proc/PID/stat's state field.
bool process_alive(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  auto close = text.rfind(')');
  if (close == std::string::npos || close + 2 >= text.size()) return false;
  char state = text[close + 2];
  return state != 'Z' && state != 'X';
}
} // namespace

TEST(LocalScheduler, JobCompletesWithEnvironmentAndOutput) {
  ScratchDir dir;
  LocalScheduler scheduler;
  check_job_completes_with_env_and_output(scheduler, dir.path());
}

TEST(LocalScheduler, JobFailsWithExitCode) {
  ScratchDir dir;
  LocalScheduler scheduler;
  check_job_fails_with_exit_code(scheduler, dir.path());
}

TEST(LocalScheduler, CancelMidRun) {
  ScratchDir dir;
  LocalScheduler scheduler;
  check_cancel_mid_run(scheduler, dir.path());
}

TEST(LocalScheduler, Array) {
  ScratchDir dir;
  LocalScheduler scheduler;
  check_array(scheduler, dir.path());
  auto r = shell_job(dir.path(), "echo $GEOTANDEM_ARRAY_INDEX");
  r.array_size = 2;
  r.stdout_path = dir.file("idx-{index}.out");
  auto ids = scheduler.submit(r);
  JobWatcher(scheduler, quick_watch()).wait_all(ids, {}, job_bound);
  EXPECT_EQ(read_text(dir.path() / "idx-0.out"), "0\n");
  EXPECT_EQ(read_text(dir.path() / "idx-1.out"), "1\n");
}

TEST(LocalScheduler, PollManyAndUnknown) {
  ScratchDir dir;
  LocalScheduler scheduler;
  check_poll_many_and_unknown(scheduler, dir.path());
}

TEST(LocalScheduler, WalltimeEndsTheJobAsTimedOut) {
  ScratchDir dir;
  LocalScheduler scheduler;
  auto r = shell_job(dir.path(), "exec sleep 600");
  r.resources.walltime = 1s;
  auto ids = scheduler.submit(r);
  auto status = JobWatcher(scheduler, quick_watch()).wait_all(ids, {}, job_bound)[ids[0]];
  EXPECT_EQ(status.state, JobState::timed_out);
}

TEST(LocalScheduler, KilledBySignalIsAFailureWithTheSignal) {
  ScratchDir dir;
  LocalScheduler scheduler;
  auto ids = scheduler.submit(shell_job(dir.path(), "kill -KILL $$"));
  auto status = JobWatcher(scheduler, quick_watch()).wait_all(ids, {}, job_bound)[ids[0]];
  EXPECT_EQ(status.state, JobState::failed);
  EXPECT_EQ(status.signal, SIGKILL);
}

TEST(LocalScheduler, DestructionCancelsAndReapsEveryChild) {
  ScratchDir dir;
  std::vector<pid_t> pids;
  {
    LocalScheduler scheduler;
    auto r = shell_job(dir.path(), "echo $$ > pid-$GEOTANDEM_ARRAY_INDEX; exec sleep 600");
    r.array_size = 3;
    scheduler.submit(r);
    for (int i = 0; i < 3; ++i) {
      auto file = dir.path() / ("pid-" + std::to_string(i));
      ASSERT_TRUE(eventually([&] { return !read_text(file).empty(); }));
      pids.push_back(std::stoi(read_text(file)));
    }
    for (pid_t pid : pids)
      EXPECT_TRUE(process_alive(pid));
  }
  for (pid_t pid : pids)
    EXPECT_FALSE(process_alive(pid)) << pid;
  for (pid_t pid : pids)
    EXPECT_FALSE(std::filesystem::exists("/proc/" + std::to_string(pid))) << "reaped: " << pid;
}

TEST(LocalScheduler, ClearErrorsForBadRequests) {
  ScratchDir dir;
  LocalScheduler scheduler;
  LaunchRequest r;
  EXPECT_THROW(scheduler.submit(r), geotandem::InvalidArgument);
  r.argv = {"geotandem-no-such-program"};
  try {
    scheduler.submit(r);
    FAIL();
  } catch (const SchedulerError& error) {
    EXPECT_NE(std::string(error.what()).find("local: cannot start `geotandem-no-such-program`"), std::string::npos)
        << error.what();
  }
  r.argv = {"true"};
  r.workdir = dir.file("missing");
  EXPECT_THROW(scheduler.submit(r), geotandem::InvalidArgument);
  r.workdir = "";
  r.array_size = 0;
  EXPECT_THROW(scheduler.submit(r), geotandem::InvalidArgument);
  EXPECT_THROW(make_scheduler("pbs"), geotandem::InvalidArgument);
  EXPECT_STREQ(make_scheduler("slurm")->name(), "slurm");
}

TEST(JobWatcher, PollsNoMoreOftenThanItsInterval) {
  ScratchDir dir;
  LocalScheduler scheduler;
  auto ids = scheduler.submit(shell_job(dir.path(), "exec sleep 600"));
  JobWatcher watcher(scheduler); // the default: 30 s
  for (int i = 0; i < 50; ++i)
    watcher.statuses(ids);
  EXPECT_EQ(watcher.polls(), 1);
  EXPECT_EQ(WatchOptions{}.interval, std::chrono::milliseconds(30000));
}

TEST(JobWatcher, CancelTokenCancelsTheJobsAndThrows) {
  ScratchDir dir;
  LocalScheduler scheduler;
  auto ids = scheduler.submit(shell_job(dir.path(), "exec sleep 600"));
  JobWatcher watcher(scheduler, quick_watch());
  geotandem::CancelToken token;
  std::thread interrupter([token] {
    std::this_thread::sleep_for(300ms);
    token.cancel(); // what a SIGINT handler does
  });
  EXPECT_THROW(watcher.wait_all(ids, token, job_bound), geotandem::Cancelled);
  interrupter.join();
  auto status = JobWatcher(scheduler, quick_watch()).wait_all(ids, {}, job_bound)[ids[0]];
  EXPECT_EQ(status.state, JobState::cancelled);
}

TEST(JobWatcher, LimitGivesAClearErrorAndLeavesTheJobs) {
  ScratchDir dir;
  LocalScheduler scheduler;
  auto ids = scheduler.submit(shell_job(dir.path(), "exec sleep 600"));
  try {
    JobWatcher(scheduler, quick_watch()).wait_all(ids, {}, 500ms);
    FAIL();
  } catch (const SchedulerError& error) {
    EXPECT_NE(std::string(error.what()).find(ids[0] + " running"), std::string::npos) << error.what();
  }
  EXPECT_EQ(scheduler.poll(ids)[ids[0]].state, JobState::running);
}
