// Worker failures as typed errors (worker_failure.hpp).
#include "worker_failure.hpp"

namespace geotandem::runtime::detail {

int failure_code(const std::exception& e) {
  if (const auto* error = dynamic_cast<const Error*>(&e)) return error->exit_code();
  return 70;
}

void throw_worker_failure(int code, const std::string& message, const std::string& worker, const std::string& hint) {
  const ErrorContext where{.worker = worker};
  switch (code) {
  case 2: throw InvalidArgument(message, where, hint);
  case 3: throw IoError(message, where, hint);
  case 4: throw FormatError(message, where, hint);
  case 5: throw DataError(message, where, hint);
  default: throw Error(message, where, hint);
  }
}

} // namespace geotandem::runtime::detail
