#pragma once
// Starts and stops worker processes. The runtime asks for one worker at a time with the command
// line to run; a cluster scheduler (schedulers/) can take this role later. LocalLauncher starts
// child processes with posix_spawn (never fork: the manager holds a ZeroMQ context).
#include <memory>
#include <string>
#include <sys/types.h>
#include <vector>

namespace geotandem::runtime {

class Launcher {
public:
  virtual ~Launcher() = default;
  // Starts one worker running `argv` (argv[0] is the program). `token` names it in logs.
  // Throws Error when the worker cannot be started.
  virtual void launch(const std::vector<std::string>& argv, const std::string& token) = 0;
  // Workers started and not known to have ended.
  virtual std::size_t running() = 0;
  // Tokens of the workers that ended since the last call (a killed worker is then known at once,
  // without waiting for its lease). A launcher that cannot tell returns nothing.
  virtual std::vector<std::string> ended() = 0;
  // Ends every worker still running: SIGTERM, then SIGKILL after `grace_seconds`. Idempotent.
  virtual void stop_all(double grace_seconds) = 0;
};

// Set by LocalLauncher in each worker's environment: the manager's process id. A worker that
// finds it asks the kernel to end it when its parent dies (local workers only; a scheduler's job
// has the scheduler's daemon as its parent).
inline constexpr const char* manager_pid_variable = "GEOTANDEM_MANAGER_PID";

class LocalLauncher final : public Launcher {
public:
  LocalLauncher() = default;
  ~LocalLauncher() override; // stop_all(2)
  LocalLauncher(const LocalLauncher&) = delete;
  LocalLauncher& operator=(const LocalLauncher&) = delete;

  void launch(const std::vector<std::string>& argv, const std::string& token) override;
  std::size_t running() override;
  std::vector<std::string> ended() override;
  void stop_all(double grace_seconds) override;
  // The children's process ids (tests stop or kill them).
  std::vector<pid_t> pids();

private:
  void reap();
  struct Child {
    pid_t pid;
    std::string token;
  };
  std::vector<Child> children_;
  std::vector<std::string> ended_;
};

} // namespace geotandem::runtime
