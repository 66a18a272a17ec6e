#pragma once
// A small logger passed down from main (no global instance). Lines go to one stream with a level
// tag; the default stream is stderr so that stdout stays clean for results (--json).

#include <iosfwd>
#include <mutex>
#include <string>
#include <string_view>

namespace geotandem {

enum class LogLevel { debug = 0, info = 1, warning = 2, error = 3, quiet = 4 };

// Parses "debug", "info", "warning", "error" or "quiet"; throws InvalidArgument otherwise.
LogLevel parse_log_level(std::string_view text);

class Logger {
public:
  explicit Logger(std::ostream& out, LogLevel level = LogLevel::info);

  LogLevel level() const noexcept { return level_; }
  void set_level(LogLevel level) noexcept { level_ = level; }
  bool enabled(LogLevel level) const noexcept { return level >= level_; }

  void log(LogLevel level, std::string_view message);
  void debug(std::string_view message) { log(LogLevel::debug, message); }
  void info(std::string_view message) { log(LogLevel::info, message); }
  void warning(std::string_view message) { log(LogLevel::warning, message); }
  void error(std::string_view message) { log(LogLevel::error, message); }

  // A logger that drops everything, for library calls made without one.
  static Logger& null();

private:
  std::ostream* out_;
  LogLevel level_;
  std::mutex mutex_;
};

} // namespace geotandem
