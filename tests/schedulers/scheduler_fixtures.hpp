#pragma once
// Helpers for the scheduler tests: environment overrides, file reading, a runner that records
// command lines (for the command-line unit tests only; the backends' end-to-end tests use the real
// ProcessCommandRunner), and waiting with a bound.

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "geotandem/schedulers/command_runner.hpp"

namespace geotandem::testing {

// Sets an environment variable for the life of the object, then restores it.
class EnvGuard {
public:
  EnvGuard(std::string name, const std::string& value) : name_(std::move(name)) {
    if (const char* old = std::getenv(name_.c_str())) old_ = old;
    ::setenv(name_.c_str(), value.c_str(), 1);
  }
  ~EnvGuard() {
    if (old_)
      ::setenv(name_.c_str(), old_->c_str(), 1);
    else
      ::unsetenv(name_.c_str());
  }
  EnvGuard(const EnvGuard&) = delete;
  EnvGuard& operator=(const EnvGuard&) = delete;

private:
  std::string name_;
  std::optional<std::string> old_;
};

// PATH with `dir` first.
inline std::string path_with(const std::string& dir) {
  const char* path = std::getenv("PATH");
  return dir + ":" + (path ? path : "/usr/bin:/bin");
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Polls `done` every 50 ms until it holds or `limit` passes; returns whether it held.
inline bool eventually(const std::function<bool()>& done, std::chrono::seconds limit = std::chrono::seconds(120)) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return done();
}

// Records every command and answers from a queue of canned results (default: success, no output).
class RecordingRunner final : public schedulers::CommandRunner {
public:
  std::vector<std::vector<std::string>> commands;
  std::vector<schedulers::CommandResult> answers;

  schedulers::CommandResult run(const std::vector<std::string>& argv, std::chrono::milliseconds) override {
    commands.push_back(argv);
    if (answers.empty()) {
      schedulers::CommandResult ok;
      ok.exit_code = 0;
      return ok;
    }
    auto answer = answers.front();
    answers.erase(answers.begin());
    return answer;
  }
  static schedulers::CommandResult answer(int exit_code, std::string out, std::string err = {}) {
    schedulers::CommandResult result;
    result.exit_code = exit_code;
    result.out = std::move(out);
    result.err = std::move(err);
    return result;
  }
};

// The real runner, with a log of the commands it ran (to count scheduler commands per poll).
class LoggingRunner final : public schedulers::CommandRunner {
public:
  std::vector<std::vector<std::string>> commands;

  schedulers::CommandResult run(const std::vector<std::string>& argv, std::chrono::milliseconds timeout) override {
    commands.push_back(argv);
    return real_.run(argv, timeout);
  }
  std::size_t count(const std::string& program) const {
    std::size_t n = 0;
    for (const auto& argv : commands)
      n += !argv.empty() && argv[0] == program;
    return n;
  }

private:
  schedulers::ProcessCommandRunner real_;
};

} // namespace geotandem::testing
