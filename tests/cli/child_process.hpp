#pragma once
// The geotandem executable as a child process that the test controls: started without a shell,
// waited for with a deadline (a hang is a failure, not a stuck test), sent signals, and optionally
// run under an address-space limit.

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace geotandem::testing {

class Child {
public:
  // Starts `geotandem ARGS...` with stdout and stderr going to files in `scratch`.
  // `address_space_bytes` > 0 sets RLIMIT_AS in the child.
  Child(const std::string& scratch, const std::vector<std::string>& args, unsigned long address_space_bytes = 0);
  ~Child(); // kills a child still running (SIGKILL) and reaps it
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  // The exit code (128 + signal for a signal death) once the child ended within `seconds`;
  // std::nullopt while it is still running after that.
  std::optional<int> wait_for(double seconds);
  void signal(int sig) const;
  std::string out() const;
  std::string err() const;
  pid_t pid() const { return pid_; }

private:
  pid_t pid_ = -1;
  bool reaped_ = false;
  int exit_code_ = -1; // once reaped
  std::string out_path_, err_path_;
};

// Runs to completion within `seconds`; a hang kills the child and returns -1.
struct ChildResult {
  int exit_code = -1;
  std::string out, err;
  bool hung = false;
};
ChildResult run_child(const std::string& scratch, const std::vector<std::string>& args, double seconds = 60,
                      unsigned long address_space_bytes = 0);

} // namespace geotandem::testing
