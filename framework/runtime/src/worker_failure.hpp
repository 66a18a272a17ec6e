#pragma once
// A worker's failed task as the manager's error: the same kind (and so the same exit code) as the
// error the worker met, so that a user's input error read by a worker exits as it would in one
// process, with a message that names the worker and says what to do. Internal to the runtime.
#include <string>

#include "geotandem/core/error.hpp"

namespace geotandem::runtime::detail {

// The exit code a worker reports for what it caught (Error::exit_code(), 70 otherwise).
int failure_code(const std::exception& e);

// Throws the error of kind `code` (2 InvalidArgument, 3 IoError, 4 FormatError, 5 DataError,
// Error otherwise) with `message`, naming `worker`, and `hint`.
[[noreturn]] void throw_worker_failure(int code, const std::string& message, const std::string& worker,
                                       const std::string& hint);

} // namespace geotandem::runtime::detail
