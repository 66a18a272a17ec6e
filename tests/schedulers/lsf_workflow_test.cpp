// `geotandem run-workflow --scheduler lsf` through the LSF stand-ins (lsf-standin/: NOT LSF, see
// its README), and submission failures that need no scheduler: sbatch missing from PATH, a hanging
// sbatch or bsub (hang-simulator/). Each failure must be a clear error naming the backend and the
// command, within a bounded time, and leave the output directory usable.
#include <signal.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "cluster_run.hpp"
#include "test_paths.hpp"

namespace geotandem::testing {
namespace {

struct LsfRun : ::testing::Test {
  ScratchDir dir;
  std::string reference = dir.file("local");
  EnvGuard path{"PATH", path_with(test_paths::lsf_standin())};
  EnvGuard state{"LSF_STANDIN_DIR", dir.file("lsf-state")};

  double reference_s = 0; // the reference run's wall time

  void SetUp() override {
    const auto t0 = std::chrono::steady_clock::now();
    const auto r = run_geotandem("-q" + shell_args(cluster_args(reference, "local", 1)));
    reference_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
};

TEST_F(LsfRun, TwoWorkerJobsGiveTheComponentsOfTheInProcessRun) {
  const std::string out = dir.file("lsf");
  const auto r = run_geotandem(shell_args(cluster_args(out, "lsf", 2)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("extracting with 2 lsf workers"), std::string::npos) << r.err;
  EXPECT_EQ(submitted_jobs(r.err).size(), 2u) << r.err;
  expect_same_components(reference + "/store", out + "/store");
}

TEST_F(LsfRun, ABkilledWorkerJobIsReplacedAndTheRunCompletes) {
  const std::string out = dir.file("bkill"), log = dir.file("bkill.log");
  const pid_t manager = spawn_geotandem(cluster_args(out, "lsf", 2), log);
  ASSERT_TRUE(wait_for_text(log, "joined; 2 connected", manager, 300)) << read_text(log);
  const std::vector<std::string> jobs = submitted_jobs(read_text(log));
  ASSERT_EQ(jobs.size(), 2u) << read_text(log);
  ASSERT_EQ(std::system(("bkill " + jobs[0] + " >/dev/null").c_str()), 0);
  ASSERT_EQ(wait_exit(manager, 600), 0) << read_text(log);
  const std::string text = read_text(log);
  if (text.find("ended") == std::string::npos && text.find("silent") == std::string::npos)
    GTEST_SKIP() << "the run finished before the job was killed (a very fast machine):\n" << text;
  EXPECT_GE(submitted_jobs(text).size(), 3u) << "a replacement job should have been submitted:\n" << text;
  expect_same_components(reference + "/store", out + "/store");
}

// Worker jobs with a short walltime (execution.resources.walltime, which the launcher exports to
// them as GEOTANDEM_WALLTIME_SECONDS) and a margin of 3 s retire before the run ends: each hands its
// surface to another worker and a replacement job is submitted as it retires; the run ends with the
// components of the in-process run. The cube is twice as long along the sweep as the others', so
// that the run takes about twice as long while its largest tasks (the last merges, whose seams are
// cross-sections) do not grow; a job works 2 s plus half the in-process run's time: long enough for
// the last merges on a slow or loaded machine (with a fixed 2 s every job retired before finishing
// them, forever), short enough that the two jobs retire before the run ends on a fast one (with the
// whole in-process time they did not, and the test had nothing to check).
TEST_F(LsfRun, WorkerJobsNearTheirWalltimeHandBackTheirSurfacesAndAreReplaced) {
  const std::string shape = "[192,96,64]", long_reference = dir.file("local-long");
  const auto t0 = std::chrono::steady_clock::now();
  const auto in_process = run_geotandem("-q" + shell_args(cluster_args(long_reference, "local", 1, shape)));
  const double long_reference_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(in_process.exit_code, 0) << in_process.err;

  EnvGuard margin{"GEOTANDEM_WALLTIME_MARGIN_SECONDS", "3"};
  const std::string out = dir.file("walltime");
  const int walltime_s = 3 + 2 + static_cast<int>(std::ceil(long_reference_s / 2));
  char walltime[32];
  std::snprintf(walltime, sizeof walltime, "%02d:%02d:%02d", walltime_s / 3600, walltime_s / 60 % 60, walltime_s % 60);
  auto args = cluster_args(out, "lsf", 2, shape);
  args.insert(args.end(), {"--set", std::string("execution.resources.walltime=") + walltime});
  const auto r = run_geotandem(shell_args(args));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  if (r.err.find(" retires (") == std::string::npos)
    GTEST_SKIP() << "the run finished before a worker reached its walltime (a very fast machine):\n" << r.err;
  EXPECT_NE(r.err.find(" hands its surface of "), std::string::npos) << r.err;
  EXPECT_GE(submitted_jobs(r.err).size(), 3u) << "a replacement job should have been submitted:\n" << r.err;
  expect_same_components(long_reference + "/store", out + "/store");
}

// Every worker job killed as soon as it is submitted: three are replaced, the fourth ends the run
// with an error naming the job and the limit (exit 1, not 70).
TEST_F(LsfRun, PastTheReplacementLimitTheRunStopsWithAClearError) {
  EnvGuard poll{"GEOTANDEM_SCHEDULER_POLL_SECONDS", "1"};
  const std::string out = dir.file("limit"), log = dir.file("limit.log");
  const pid_t manager = spawn_geotandem(cluster_args(out, "lsf", 1), log);
  std::set<std::string> killed;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(300);
  while (alive(manager) && std::chrono::steady_clock::now() < until) {
    for (const std::string& job : submitted_jobs(read_text(log)))
      if (killed.insert(job).second) std::system(("bkill " + job + " >/dev/null 2>&1").c_str());
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const int code = wait_exit(manager, 60);
  const std::string text = read_text(log);
  EXPECT_EQ(code, 1) << text;
  EXPECT_NE(text.find("lsf: job "), std::string::npos) << text;
  EXPECT_NE(text.find("has already replaced 3 lost or killed job(s), its limit"), std::string::npos) << text;
  // Four ended jobs reach the policy; the manager may have started one more after a heartbeat death
  // before the fourth job's end was polled.
  EXPECT_GE(killed.size(), 4u) << text;
  EXPECT_LE(killed.size(), 5u) << text;
}

TEST_F(LsfRun, NoSuchQueueIsAClearError) {
  auto args = cluster_args(dir.file("noqueue"), "lsf", 2);
  args.insert(args.end(), {"--set", "execution.resources.queue=no_such_queue"});
  const auto r = run_geotandem(shell_args(args));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.exit_code, 70);
  EXPECT_NE(r.err.find("lsf: `bsub"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("No such queue"), std::string::npos) << r.err;
}

TEST(SubmissionFailures, SbatchMissingFromPathIsAClearError) {
  ScratchDir dir;
  const std::string empty = dir.file("empty-bin");
  std::filesystem::create_directories(empty);
  EnvGuard path{"PATH", empty};
  const auto r = run_geotandem(shell_args(cluster_args(dir.file("out"), "slurm", 2)));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.exit_code, 70);
  EXPECT_NE(r.err.find("slurm: `sbatch"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("could not be started"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("PATH"), std::string::npos) << r.err;
}

TEST(SubmissionFailures, AHangingSbatchOrBsubIsStoppedAtTheTimeout) {
  ScratchDir dir;
  EnvGuard path{"PATH", path_with(test_paths::hang_simulator())};
  EnvGuard timeout{"GEOTANDEM_SCHEDULER_COMMAND_TIMEOUT", "3"};
  for (const std::string backend : {"slurm", "lsf"}) {
    const auto start = std::chrono::steady_clock::now();
    const auto r = run_geotandem(shell_args(cluster_args(dir.file(backend), backend, 2)));
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(120)) << backend;
    EXPECT_NE(r.exit_code, 0) << backend;
    EXPECT_NE(r.exit_code, 70) << backend;
    const std::string command = backend == "slurm" ? "slurm: `sbatch" : "lsf: `bsub";
    EXPECT_NE(r.err.find(command), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("hung"), std::string::npos) << r.err;
  }
}

} // namespace
} // namespace geotandem::testing
