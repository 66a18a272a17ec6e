// Slurm's command lines and output formats. The outputs below are what Slurm 22.05 printed for
// these commands on a private test cluster (see scripts/slurm-test-cluster.sh).
#include <gtest/gtest.h>

#include <algorithm>

#include "geotandem/schedulers/slurm_commands.hpp"
#include "geotandem/schedulers/slurm_scheduler.hpp"
#include "scheduler_fixtures.hpp"

using namespace geotandem::schedulers;
using namespace std::chrono_literals;

namespace {
bool has(const std::vector<std::string>& argv, const std::vector<std::string>& run) {
  return std::search(argv.begin(), argv.end(), run.begin(), run.end()) != argv.end();
}
LaunchRequest request() {
  LaunchRequest r;
  r.argv = {"/opt/geo tandem/bin/geotandem", "worker", "--endpoint", "tcp://n1:5555"};
  r.env = {{"OMP_NUM_THREADS", "4"}, {"NOTE", "it's"}};
  r.workdir = "/scratch/run 1";
  r.stdout_path = "logs/worker-{job}-{index}.out";
  r.name = "gt-worker";
  r.array_size = 3;
  r.token = "tok-123";
  r.resources.cpus = 4;
  r.resources.memory_mb = 8000;
  r.resources.walltime = 2h + 30min + 5s;
  r.resources.queue = "compute";
  r.resources.account = "geo";
  r.resources.extra_args = {"--qos=long", "--exclusive"};
  return r;
}
} // namespace

TEST(SlurmCommands, SbatchCarriesEveryResourceAndNoRequeue) {
  auto argv = slurm::sbatch_command(request());
  EXPECT_EQ(argv[0], "sbatch");
  EXPECT_TRUE(has(argv, {"--parsable"}));
  EXPECT_TRUE(has(argv, {"--no-requeue"}));
  EXPECT_TRUE(has(argv, {"-J", "gt-worker"}));
  EXPECT_TRUE(has(argv, {"-D", "/scratch/run 1"}));
  EXPECT_TRUE(has(argv, {"-o", "logs/worker-%A-%a.out"}));
  EXPECT_TRUE(has(argv, {"--array=0-2"}));
  EXPECT_TRUE(has(argv, {"-n", "1", "-c", "4"}));
  EXPECT_TRUE(has(argv, {"--mem=8000M"}));
  EXPECT_TRUE(has(argv, {"--time=2:30:05"}));
  EXPECT_TRUE(has(argv, {"-p", "compute"}));
  EXPECT_TRUE(has(argv, {"-A", "geo"}));
  EXPECT_TRUE(has(argv, {"--qos=long", "--exclusive"}));
  ASSERT_GE(argv.size(), 2u);
  EXPECT_EQ(argv[argv.size() - 2], "--wrap");
  EXPECT_EQ(argv.back(), "exec env 'GEOTANDEM_LAUNCH_TOKEN=tok-123' 'NOTE=it'\\''s' 'OMP_NUM_THREADS=4' "
                         "'/opt/geo tandem/bin/geotandem' 'worker' '--endpoint' 'tcp://n1:5555'");
}

TEST(SlurmCommands, SingleJobUsesJobIdPatternAndEscapesPercent) {
  LaunchRequest r;
  r.argv = {"true"};
  r.stdout_path = "out-{job}-100%.txt";
  auto argv = slurm::sbatch_command(r);
  EXPECT_TRUE(has(argv, {"-o", "out-%j-100%%.txt"}));
  EXPECT_FALSE(std::any_of(argv.begin(), argv.end(), [](auto& a) { return a.rfind("--array", 0) == 0; }));
  EXPECT_FALSE(has(argv, {"-p"})) << "no partition given: the cluster's default";
  EXPECT_EQ(slurm::format_walltime(59), "0:00:59");
  EXPECT_EQ(slurm::format_walltime(90061), "25:01:01");
}

TEST(SlurmCommands, ParsesSbatchParsableOutput) {
  EXPECT_EQ(slurm::parse_sbatch_output("4711\n"), "4711");
  EXPECT_EQ(slurm::parse_sbatch_output("4711;cluster2\n"), "4711");
  EXPECT_EQ(slurm::parse_sbatch_output("sbatch: warning: something\n4712\n"), "4712");
  EXPECT_FALSE(slurm::parse_sbatch_output("Submitted batch job\n"));
  EXPECT_FALSE(slurm::parse_sbatch_output(""));
  EXPECT_EQ(slurm::element_ids("9", 1), std::vector<JobId>{"9"});
  EXPECT_EQ(slurm::element_ids("9", 3), (std::vector<JobId>{"9_0", "9_1", "9_2"}));
}

TEST(SlurmCommands, ParsesSqueueLines) {
  auto argv = slurm::squeue_command({"1", "2_1", "2_2"});
  EXPECT_EQ(argv,
            (std::vector<std::string>{"squeue", "-h", "-t", "all", "-r", "-j", "1,2_1,2_2", "-o", "%i|%T|%r|%N"}));
  const std::string out = "1|FAILED|NonZeroExitCode|localhost\n"
                          "2_1|PENDING|Resources|\n"
                          "2_2|RUNNING|None|localhost\n"
                          "3|COMPLETED|None|localhost\n"
                          "4|CANCELLED|None|localhost\n"
                          "5|TIMEOUT|TimeLimit|n3\n"
                          "6|NODE_FAIL|NodeDown|n4\n"
                          "garbage line\n";
  auto reports = slurm::parse_squeue_output(out);
  ASSERT_EQ(reports.size(), 7u);
  EXPECT_EQ(reports[0].id, "1");
  EXPECT_EQ(reports[0].status.state, JobState::failed);
  EXPECT_EQ(reports[0].status.reason, "NonZeroExitCode");
  EXPECT_EQ(reports[1].status.state, JobState::pending);
  EXPECT_EQ(reports[1].status.host, "");
  EXPECT_EQ(reports[2].status.state, JobState::running);
  EXPECT_EQ(reports[2].status.reason, "");
  EXPECT_EQ(reports[3].status.state, JobState::completed);
  EXPECT_EQ(reports[3].status.exit_code, 0);
  EXPECT_EQ(reports[4].status.state, JobState::cancelled);
  EXPECT_EQ(reports[5].status.state, JobState::timed_out);
  EXPECT_EQ(reports[6].status.state, JobState::node_failure);
  EXPECT_EQ(reports[6].status.host, "n4");
  EXPECT_TRUE(slurm::squeue_reports_unknown_ids("slurm_load_jobs error: Invalid job id specified\n"));
  EXPECT_FALSE(slurm::squeue_reports_unknown_ids("slurm_load_jobs error: Unable to contact slurm controller\n"));
}

TEST(SlurmCommands, ParsesScontrolExitCode) {
  JobStatus s;
  slurm::parse_scontrol_exit("JobId=1 JobName=wrap JobState=FAILED Reason=NonZeroExitCode Dependency=(null) "
                             "Requeue=0 Restarts=0 BatchFlag=1 Reboot=0 ExitCode=3:0 DerivedExitCode=0:0 RunTime=0",
                             s);
  EXPECT_EQ(s.exit_code, 3);
  EXPECT_FALSE(s.signal);
  JobStatus k;
  slurm::parse_scontrol_exit("JobId=7 JobState=FAILED ExitCode=0:9 RunTime=00:00:01", k);
  EXPECT_EQ(k.signal, 9);
}

TEST(SlurmCommands, StateNamesAndCodes) {
  EXPECT_EQ(slurm::state_from_slurm("PD"), JobState::pending);
  EXPECT_EQ(slurm::state_from_slurm("COMPLETING"), JobState::running);
  EXPECT_EQ(slurm::state_from_slurm("CANCELLED by 0"), JobState::cancelled);
  EXPECT_EQ(slurm::state_from_slurm("OUT_OF_MEMORY"), JobState::failed);
  EXPECT_EQ(slurm::state_from_slurm("PREEMPTED"), JobState::cancelled);
  EXPECT_EQ(slurm::state_from_slurm("BOOT_FAIL"), JobState::node_failure);
  EXPECT_EQ(slurm::state_from_slurm("SOMETHING_NEW"), JobState::running);
}

TEST(SlurmScheduler, OnePollCommandForManyJobsAndExitCodesOncePerFailure) {
  auto runner = std::make_shared<geotandem::testing::RecordingRunner>();
  SchedulerOptions options;
  options.runner = runner;
  options.cancel_on_destruction = false;
  SlurmScheduler scheduler(options);
  LaunchRequest r;
  r.argv = {"true"};
  r.array_size = 3;
  runner->answers.push_back(geotandem::testing::RecordingRunner::answer(0, "50\n"));
  auto ids = scheduler.submit(r);
  ASSERT_EQ(ids, (std::vector<JobId>{"50_0", "50_1", "50_2"}));
  runner->answers.push_back(geotandem::testing::RecordingRunner::answer(
      0, "50_0|RUNNING|None|n1\n50_1|FAILED|NonZeroExitCode|n2\n50_2|PENDING|Priority|\n"));
  runner->answers.push_back(geotandem::testing::RecordingRunner::answer(0, "JobId=51 ExitCode=4:0 x"));
  auto statuses = scheduler.poll(ids);
  ASSERT_EQ(runner->commands.size(), 3u);
  EXPECT_EQ(runner->commands[1][0], "squeue");
  EXPECT_EQ(runner->commands[2], (std::vector<std::string>{"scontrol", "show", "job", "-o", "50_1"}));
  EXPECT_EQ(statuses["50_1"].exit_code, 4);
  EXPECT_EQ(statuses["50_2"].reason, "Priority");
  // The next poll asks only about the unfinished jobs; 50_0 is gone before we saw it end.
  runner->answers.push_back(geotandem::testing::RecordingRunner::answer(0, "50_2|RUNNING|None|n1\n"));
  statuses = scheduler.poll(ids);
  EXPECT_EQ(runner->commands[3][6], "50_0,50_2,50") << "the array's own record too";
  EXPECT_EQ(statuses["50_0"].state, JobState::vanished);
  EXPECT_EQ(statuses["50_0"].host, "n1");
  EXPECT_EQ(statuses["50_1"].state, JobState::failed);
  EXPECT_EQ(statuses["50_2"].state, JobState::running);
}

TEST(SlurmScheduler, SubmissionRefusalNamesBackendCommandAndHint) {
  auto runner = std::make_shared<geotandem::testing::RecordingRunner>();
  SchedulerOptions options;
  options.runner = runner;
  SlurmScheduler scheduler(options);
  runner->answers.push_back(geotandem::testing::RecordingRunner::answer(
      1, "",
      "sbatch: error: invalid partition specified: nosuch\nsbatch: error: Batch job submission failed: "
      "Invalid partition name specified\n"));
  LaunchRequest r;
  r.argv = {"true"};
  r.resources.queue = "nosuch";
  try {
    scheduler.submit(r);
    FAIL();
  } catch (const SchedulerError& error) {
    std::string what = error.what();
    EXPECT_EQ(what.rfind("slurm: `sbatch ", 0), 0u) << what;
    EXPECT_NE(what.find("invalid partition specified: nosuch"), std::string::npos) << what;
    EXPECT_NE(what.find("sinfo"), std::string::npos) << what;
  }
  EXPECT_TRUE(scheduler.submitted().empty());
}

TEST(SlurmCommands, CancelledPendingArrayCollapsesIntoOneRecord) {
  // Slurm 22.05: an array whose pending elements were all cancelled before any started is shown
  // as one record under the array's id, and no longer under its elements' ids.
  EXPECT_EQ(slurm::squeue_query_ids({"6_0", "6_1", "7"}), (std::vector<JobId>{"6_0", "6_1", "7", "6"}));
  auto reports =
      slurm::match_reports({"6_0", "6_1", "7", "8_0"},
                           slurm::parse_squeue_output("6|CANCELLED|None|\n7|RUNNING|None|n1\n8_1|RUNNING|None|n1\n"));
  ASSERT_EQ(reports.size(), 3u) << "8_0 is reported by nobody";
  EXPECT_EQ(reports[0].id, "6_0");
  EXPECT_EQ(reports[0].status.state, JobState::cancelled);
  EXPECT_EQ(reports[1].id, "6_1");
  EXPECT_EQ(reports[2].id, "7");
}
