#pragma once
// Test helpers: a fresh scratch directory per test, and running the geotandem executable as a real
// child process.

#include <filesystem>
#include <string>

namespace geotandem::testing {

// A new empty directory under the build tree, named after the running test; removed on
// destruction unless the test failed (so that a failure leaves its files to look at).
class ScratchDir {
public:
  ScratchDir();
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

private:
  std::filesystem::path path_;
};

struct CommandResult {
  int exit_code = -1;
  std::string out; // stdout
  std::string err; // stderr
};

// Runs `geotandem ARGS` (a shell-quoted argument string) and captures its output.
CommandResult run_geotandem(const std::string& args);

} // namespace geotandem::testing
