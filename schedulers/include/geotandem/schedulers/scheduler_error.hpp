#pragma once
// The error every backend throws: it names the backend and the command that failed, says what the
// scheduler answered, and what to do.

#include <string>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/schedulers/command_runner.hpp"

namespace geotandem::schedulers {

class SchedulerError : public geotandem::Error {
public:
  // "slurm: `sbatch --parsable ...` failed (exit 1): sbatch: error: invalid partition ... (hint)"
  SchedulerError(const std::string& backend, const std::string& message, const std::string& hint = {});
  const std::string& backend() const noexcept { return backend_; }

private:
  std::string backend_;
};

// A scheduler command's failure as an error: not on PATH, timed out, killed, non-zero exit.
SchedulerError command_failed(const std::string& backend, const std::vector<std::string>& argv,
                              const CommandResult& result, const std::string& hint = {});

} // namespace geotandem::schedulers
