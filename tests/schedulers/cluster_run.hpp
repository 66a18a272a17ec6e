#pragma once
// `geotandem run-workflow` with its workers as scheduler jobs, for the Slurm and LSF end-to-end
// tests: the quickstart recipe on a smaller cube, a reference run in one process, the component
// comparison, and waiting on a log file for the lines a running manager prints.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "../runtime/process_fixtures.hpp"
#include "scratch.hpp"
#include "test_paths.hpp"

namespace geotandem::testing {

// Sets an environment variable for the life of the guard (run_geotandem and spawn_geotandem
// inherit the test's environment).
class EnvGuard {
public:
  EnvGuard(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value.c_str(), 1);
  }
  ~EnvGuard() {
    if (old_)
      setenv(name_, old_->c_str(), 1);
    else
      unsetenv(name_);
  }
  EnvGuard(const EnvGuard&) = delete;
  EnvGuard& operator=(const EnvGuard&) = delete;

private:
  const char* name_;
  std::optional<std::string> old_;
};

inline std::string path_with(const std::string& dir) {
  const char* path = std::getenv("PATH");
  return dir + ":" + (path ? path : "/usr/bin:/bin");
}

inline std::string quickstart() {
  return test_paths::workflows() + "/quickstart.yaml";
}

// The quickstart recipe on a 96x96x64 cube in leaves of 8 cells (several seconds of work for two
// workers, so that a job can be cancelled while the run goes on), into `out`.
inline std::vector<std::string> cluster_args(const std::string& out, const std::string& scheduler, int workers,
                                             const std::string& shape = "[96,96,64]") {
  return {"--log-level",  "info",
          "run-workflow", quickstart(),
          "--set",        "input.synthetic.shape=" + shape,
          "--set",        "steps.extract.block_size=8",
          "--set",        "output.directory=" + out,
          "--set",        "execution.workers=" + std::to_string(workers),
          "--scheduler",  scheduler};
}

inline std::string shell_args(const std::vector<std::string>& args) {
  std::string text;
  for (const std::string& a : args)
    text += " '" + a + "'";
  return text;
}

// Same keys, volumes within 0.5 %.
inline void expect_same_components(const std::string& reference_store, const std::string& store) {
  const auto reference = components_of(reference_store, false);
  const auto got = components_of(store, false);
  ASSERT_GT(reference.size(), 5u);
  ASSERT_EQ(got.size(), reference.size()) << store;
  for (const auto& [key, ref] : reference) {
    ASSERT_TRUE(got.count(key)) << "component " << key << " missing from " << store;
    EXPECT_NEAR(got.at(key).volume, ref.volume, 0.005 * std::abs(ref.volume) + 1e-9) << "component " << key;
    EXPECT_EQ(got.at(key).closed, ref.closed) << "component " << key;
  }
}

// The job ids a log reports as "submitted as job ID", in order.
inline std::vector<std::string> submitted_jobs(const std::string& log) {
  std::vector<std::string> ids;
  static const std::regex re("submitted as job ([^ ]+) ");
  for (auto it = std::sregex_iterator(log.begin(), log.end(), re); it != std::sregex_iterator(); ++it)
    ids.push_back((*it)[1]);
  return ids;
}

// Waits until `log_path` contains `text` or the process ended or `timeout_s` passed.
inline bool wait_for_text(const std::string& log_path, const std::string& text, pid_t pid, double timeout_s) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < until) {
    if (read_text(log_path).find(text) != std::string::npos) return true;
    if (!alive(pid)) return read_text(log_path).find(text) != std::string::npos;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

} // namespace geotandem::testing
