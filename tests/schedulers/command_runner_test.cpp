// The real command runner: output, exit codes, missing programs, and a bounded time for hangs.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <signal.h>

#include "geotandem/schedulers/command_runner.hpp"
#include "geotandem/schedulers/scheduler_error.hpp"

using namespace geotandem::schedulers;
using namespace std::chrono_literals;

TEST(CommandRunner, CapturesOutputAndExitCode) {
  ProcessCommandRunner runner;
  auto result = runner.run({"sh", "-c", "echo out; echo err >&2; exit 3"}, 60s);
  EXPECT_EQ(result.exit_code, 3);
  EXPECT_EQ(result.out, "out\n");
  EXPECT_EQ(result.err, "err\n");
  EXPECT_FALSE(result.timed_out);
  EXPECT_FALSE(result.ok());
  EXPECT_TRUE(runner.run({"true"}, 60s).ok());
}

TEST(CommandRunner, CapturesLargeOutputWithoutDeadlock) {
  ProcessCommandRunner runner;
  auto result = runner.run({"sh", "-c", "head -c 1000000 /dev/zero | tr '\\0' x; head -c 300000 /dev/zero >&2"}, 60s);
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_EQ(result.out.size(), 1000000u);
  EXPECT_EQ(result.err.size(), 300000u);
}

TEST(CommandRunner, ReportsAProgramNotOnPath) {
  ProcessCommandRunner runner;
  auto result = runner.run({"geotandem-no-such-program"}, 60s);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.spawn_error.find("not found on PATH"), std::string::npos) << result.spawn_error;
  auto error = command_failed("slurm", {"geotandem-no-such-program", "-x"}, result);
  std::string what = error.what();
  EXPECT_NE(what.find("slurm: `geotandem-no-such-program -x`"), std::string::npos) << what;
  EXPECT_NE(what.find("PATH"), std::string::npos) << what;
}

TEST(CommandRunner, KillsAHangingCommandAndItsChildrenWithinTheTimeout) {
  ProcessCommandRunner runner;
  const auto start = std::chrono::steady_clock::now();
  // The shell starts a child that would keep the pipes open: the whole group must go. The timeout
  // leaves the shell time to start and print on a loaded machine, where a process takes a second
  // or more to start.
  auto result = runner.run({"sh", "-c", "echo started >&2; sleep 300 & sleep 300"}, 10s);
  const auto took = std::chrono::steady_clock::now() - start;
  EXPECT_TRUE(result.timed_out);
  EXPECT_FALSE(result.ok());
  EXPECT_LT(took, 100s) << "bounded by the timeout, with generous slack for a loaded machine";
  EXPECT_GE(took, 10s) << "never before the timeout (it once stopped up to a millisecond early)";
  std::string what = command_failed("lsf", {"bjobs", "-noheader"}, result).what();
  EXPECT_NE(what.find("lsf: `bjobs -noheader` hung"), std::string::npos) << what;
  EXPECT_NE(what.find("started"), std::string::npos) << "what it printed before hanging helps: " << what;
}

TEST(CommandRunner, DoesNotWaitForADaemonThatKeepsThePipesOpen) {
  ProcessCommandRunner runner;
  const auto start = std::chrono::steady_clock::now();
  auto result = runner.run({"sh", "-c", "(sleep 30 & echo $! >&2) ; echo submitted"}, 60s);
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_EQ(result.out, "submitted\n");
  EXPECT_LT(std::chrono::steady_clock::now() - start, 25s);
  if (!result.err.empty()) ::kill(std::stoi(result.err), SIGKILL); // the "daemon" is ours to end
}

TEST(CommandRunner, DescribesCommandsWithQuotes) {
  EXPECT_EQ(describe_command({"sbatch", "--wrap", "exec env 'A=b c'", "-p", "x"}),
            "sbatch --wrap 'exec env '\\''A=b c'\\''' -p x");
}

TEST(CommandRunner, IgnoredSigchldIsAClearErrorNotAHang) {
  auto old = std::signal(SIGCHLD, SIG_IGN); // children are reaped by the kernel: no exit status
  ProcessCommandRunner runner;
  const auto start = std::chrono::steady_clock::now();
  auto result = runner.run({"sh", "-c", "echo hi"}, 60s);
  std::signal(SIGCHLD, old);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.spawn_error.find("SIGCHLD"), std::string::npos) << result.spawn_error;
  EXPECT_LT(std::chrono::steady_clock::now() - start, 30s);
}
