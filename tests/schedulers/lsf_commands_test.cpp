// LSF's command lines and output formats. The sample outputs are written from IBM's documented
// formats (bsub's submission line, bjobs -o with a delimiter, bkill's messages); no real LSF was
// available to record them. See schedulers/README.md.
#include <gtest/gtest.h>

#include <algorithm>

#include "geotandem/schedulers/lsf_commands.hpp"
#include "geotandem/schedulers/lsf_scheduler.hpp"
#include "scheduler_fixtures.hpp"

using namespace geotandem::schedulers;
using geotandem::testing::RecordingRunner;
using namespace std::chrono_literals;

namespace {
bool has(const std::vector<std::string>& argv, const std::vector<std::string>& run) {
  return std::search(argv.begin(), argv.end(), run.begin(), run.end()) != argv.end();
}
} // namespace

TEST(LsfCommands, BsubCarriesEveryResource) {
  LaunchRequest r;
  r.argv = {"geotandem", "worker", "a b"};
  r.env = {{"K", "v"}};
  r.workdir = "/scratch/run";
  r.stdout_path = "w-{job}-{index}.out";
  r.stderr_path = "w-{job}-{index}.err";
  r.name = "gtw";
  r.array_size = 4;
  r.token = "T";
  r.resources.cpus = 8;
  r.resources.memory_mb = 4096;
  r.resources.walltime = 90min + 1s;
  r.resources.queue = "normal";
  r.resources.account = "geoproj";
  r.resources.extra_args = {"-x"};
  auto argv = lsf::bsub_command(r);
  EXPECT_EQ(argv[0], "bsub");
  EXPECT_TRUE(has(argv, {"-J", "gtw[1-4]"}));
  EXPECT_TRUE(has(argv, {"-n", "8", "-R", "span[hosts=1]"}));
  EXPECT_TRUE(has(argv, {"-q", "normal"}));
  EXPECT_TRUE(has(argv, {"-W", "1:31"})) << "rounded up to the next minute";
  EXPECT_TRUE(has(argv, {"-o", "w-%J-%I.out"}));
  EXPECT_TRUE(has(argv, {"-e", "w-%J-%I.err"}));
  EXPECT_TRUE(has(argv, {"-P", "geoproj"}));
  EXPECT_TRUE(has(argv, {"-M", "4096MB"}));
  EXPECT_TRUE(has(argv, {"-cwd", "/scratch/run"}));
  EXPECT_TRUE(has(argv, {"-x"}));
  EXPECT_EQ(argv.back(), "exec env 'GEOTANDEM_LAUNCH_TOKEN=T' 'K=v' 'geotandem' 'worker' 'a b'");
  EXPECT_EQ(lsf::format_walltime(60), "0:01");
  EXPECT_EQ(lsf::format_walltime(1), "0:01");
  EXPECT_EQ(lsf::format_walltime(36000), "10:00");
}

TEST(LsfCommands, ParsesSubmissionLines) {
  EXPECT_EQ(lsf::parse_bsub_output("Job <1234> is submitted to queue <normal>.\n"), "1234");
  EXPECT_EQ(lsf::parse_bsub_output("Job <77> is submitted to default queue <short>.\n"), "77");
  EXPECT_EQ(lsf::parse_bsub_output("Warning: project geo is not defined; using default\n"
                                   "Job <78> is submitted to queue <long>.\n"),
            "78");
  EXPECT_FALSE(lsf::parse_bsub_output("nosuch: No such queue. Job not submitted.\n"));
  EXPECT_FALSE(lsf::parse_bsub_output("Job <> is submitted to queue <x>.\n"));
  EXPECT_EQ(lsf::element_ids("5", 2), (std::vector<JobId>{"5[1]", "5[2]"}));
}

TEST(LsfCommands, ParsesBjobsLines) {
  EXPECT_EQ(lsf::bjobs_command({"5", "6[2]"}),
            (std::vector<std::string>{"bjobs", "-noheader", "-o", lsf::bjobs_format, "5", "6[2]"}));
  const std::string out = "5^0^RUN^-^hostA\n"
                          "6^2^PEND^-^-\n"
                          "7^0^DONE^-^4*hostB:4*hostC\n"
                          "8^0^EXIT^3^hostA\n"
                          "9[4]^4^SSUSP^-^hostD\n"
                          "10^0^UNKWN^-^hostE\n"
                          "Job <11> is not found\n"
                          "12^0^ZOMBI^-^hostF\n";
  auto reports = lsf::parse_bjobs_output(out);
  ASSERT_EQ(reports.size(), 7u);
  EXPECT_EQ(reports[0].id, "5");
  EXPECT_EQ(reports[0].status.state, JobState::running);
  EXPECT_EQ(reports[1].id, "6[2]");
  EXPECT_EQ(reports[1].status.state, JobState::pending);
  EXPECT_EQ(reports[1].status.host, "");
  EXPECT_EQ(reports[2].status.state, JobState::completed);
  EXPECT_EQ(reports[2].status.exit_code, 0);
  EXPECT_EQ(reports[2].status.host, "4*hostB:4*hostC");
  EXPECT_EQ(reports[3].status.state, JobState::failed);
  EXPECT_EQ(reports[3].status.exit_code, 3);
  EXPECT_EQ(reports[4].id, "9[4]") << "LSB_BJOBS_DISPLAY_ENH=Y shows the index in the jobid column";
  EXPECT_EQ(reports[4].status.state, JobState::running);
  EXPECT_EQ(reports[4].status.reason, "LSF state SSUSP");
  EXPECT_EQ(reports[5].status.state, JobState::node_failure);
  EXPECT_EQ(reports[6].id, "12");
  EXPECT_EQ(reports[6].status.state, JobState::node_failure);
}

TEST(LsfCommands, BkillMessages) {
  EXPECT_EQ(lsf::bkill_command({"5", "6[1]"}), (std::vector<std::string>{"bkill", "5", "6[1]"}));
  EXPECT_TRUE(lsf::bkill_reports_finished("Job <5>: Job has already finished\n"));
  EXPECT_TRUE(lsf::bkill_reports_finished("Job <5> is being terminated\nJob <6>: No matching job found\n"));
  EXPECT_FALSE(lsf::bkill_reports_finished("Job <5>: User permission denied\n"));
  EXPECT_FALSE(lsf::bkill_reports_finished("LSF is down. Please wait ...\n"));
}

TEST(LsfScheduler, BjobsNonZeroWithValidLinesIsNotAnError) {
  auto runner = std::make_shared<RecordingRunner>();
  SchedulerOptions options;
  options.runner = runner;
  options.cancel_on_destruction = false;
  LsfScheduler scheduler(options);
  LaunchRequest r;
  r.argv = {"true"};
  runner->answers.push_back(RecordingRunner::answer(0, "Job <20> is submitted to queue <normal>.\n"));
  runner->answers.push_back(RecordingRunner::answer(0, "Job <21> is submitted to queue <normal>.\n"));
  auto a = scheduler.submit(r), b = scheduler.submit(r);
  runner->answers.push_back(RecordingRunner::answer(255, "20^0^DONE^-^hostA\n", "Job <21> is not found\n"));
  auto statuses = scheduler.poll({a[0], b[0]});
  ASSERT_EQ(runner->commands.size(), 3u) << "one bjobs for both";
  EXPECT_EQ(statuses[a[0]].state, JobState::completed);
  EXPECT_EQ(statuses[b[0]].state, JobState::vanished);
}

TEST(LsfScheduler, BjobsFailureWithoutJobLinesIsAnError) {
  auto runner = std::make_shared<RecordingRunner>();
  SchedulerOptions options;
  options.runner = runner;
  options.cancel_on_destruction = false;
  LsfScheduler scheduler(options);
  LaunchRequest r;
  r.argv = {"true"};
  runner->answers.push_back(RecordingRunner::answer(0, "Job <30> is submitted to queue <normal>.\n"));
  auto ids = scheduler.submit(r);
  runner->answers.push_back(RecordingRunner::answer(255, "", "LSF is down. Please wait ...\n"));
  try {
    scheduler.poll(ids);
    FAIL();
  } catch (const SchedulerError& error) {
    std::string what = error.what();
    EXPECT_NE(what.find("lsf: `bjobs -noheader"), std::string::npos) << what;
    EXPECT_NE(what.find("LSF is down"), std::string::npos) << what;
  }
  // The job is still ours and still pending: an outage is not a verdict.
  runner->answers.push_back(RecordingRunner::answer(0, "30^0^RUN^-^hostA\n"));
  EXPECT_EQ(scheduler.poll(ids)[ids[0]].state, JobState::running);
}
