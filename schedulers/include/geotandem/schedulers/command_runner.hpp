#pragma once
// Runs scheduler commands (sbatch, squeue, bsub, ...). Injectable, so that tests can record the
// command lines a backend generates; the real one spawns the program with posix_spawnp.

#include <chrono>
#include <string>
#include <vector>

namespace geotandem::schedulers {

struct CommandResult {
  int exit_code = -1;      // -1 when the program did not exit normally
  int signal = 0;          // the signal that ended it, 0 if none
  bool timed_out = false;  // killed by us at the timeout
  std::string spawn_error; // non-empty when the program could not be started (not on PATH...)
  std::string out;         // its stdout
  std::string err;         // its stderr
  bool ok() const noexcept { return spawn_error.empty() && !timed_out && exit_code == 0; }
};

class CommandRunner {
public:
  virtual ~CommandRunner() = default;
  // Runs argv (argv[0] looked up on PATH) with stdin from /dev/null. Never throws for the
  // command's own failures: they are in the result. Returns within about `timeout`.
  virtual CommandResult run(const std::vector<std::string>& argv, std::chrono::milliseconds timeout) = 0;
};

// The real runner. The command runs in its own process group; at the timeout the whole group is
// killed (SIGKILL), so a hanging scheduler client and anything it started are gone.
class ProcessCommandRunner final : public CommandRunner {
public:
  CommandResult run(const std::vector<std::string>& argv, std::chrono::milliseconds timeout) override;
};

// "sbatch --parsable --wrap 'x y'": argv joined for messages, quoted where needed.
std::string describe_command(const std::vector<std::string>& argv);

} // namespace geotandem::schedulers
