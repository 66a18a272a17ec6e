#pragma once
// Typed errors with context. Every error says what failed, where (file, line, column, block,
// worker: whatever applies) and, when known, what the user can do about it.

#include <optional>
#include <stdexcept>
#include <string>

namespace geotandem {

// Where an error happened. Every field is optional; what() prints the ones that are set.
struct ErrorContext {
  std::string file;           // a path the user gave or the program wrote
  std::optional<long> line;   // 1-based, in a text file (recipe, sidecar)
  std::optional<long> column; // 1-based
  std::string block;          // a block or box, as text ("block 3 [0:128,0:128,0:64]")
  std::string worker;         // a worker id in the distributed runtime
};

// Base of every geotandem error. what() is the full message: "<where>: <message> (<hint>)".
class Error : public std::runtime_error {
public:
  Error(std::string message, ErrorContext context = {}, std::string hint = {});

  const std::string& message() const noexcept { return message_; }
  const ErrorContext& context() const noexcept { return context_; }
  const std::string& hint() const noexcept { return hint_; }

  // Process exit code the CLI uses for this kind of error.
  virtual int exit_code() const noexcept { return 1; }

private:
  std::string message_;
  ErrorContext context_;
  std::string hint_;
};

// The user's input is wrong: a bad argument, an out-of-range parameter, a box outside the cube.
class InvalidArgument : public Error {
public:
  using Error::Error;
  int exit_code() const noexcept override { return 2; }
};

// A file could not be opened, read or written.
class IoError : public Error {
public:
  using Error::Error;
  int exit_code() const noexcept override { return 3; }
};

// A file was read but its content is not what it should be: unknown format, truncated, bad
// checksum, wrong version.
class FormatError : public Error {
public:
  using Error::Error;
  int exit_code() const noexcept override { return 4; }
};

// The data contains something the requested operation refuses (NaN under the "error" policy...).
class DataError : public Error {
public:
  using Error::Error;
  int exit_code() const noexcept override { return 5; }
};

// A long operation was cancelled through its CancelToken.
class Cancelled : public Error {
public:
  Cancelled();
  int exit_code() const noexcept override { return 130; }
};

// Throws an error of the same kind as `e` (the same exit code), its context and hint kept, with
// `note` appended to its message: where in a larger task it happened ("in the recipe's step ...").
// A Cancelled error is thrown again as it is.
[[noreturn]] void throw_with_note(const Error& e, const std::string& note);

// Composes the text of what(); exposed for messages built elsewhere (logs, reports).
std::string format_error(const std::string& message, const ErrorContext& context, const std::string& hint);

} // namespace geotandem
