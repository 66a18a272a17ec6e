#include "geotandem/core/log.hpp"

#include <ostream>
#include <sstream>
#include <string>

#include "geotandem/core/error.hpp"

namespace geotandem {

LogLevel parse_log_level(std::string_view text) {
  if (text == "debug") return LogLevel::debug;
  if (text == "info") return LogLevel::info;
  if (text == "warning") return LogLevel::warning;
  if (text == "error") return LogLevel::error;
  if (text == "quiet") return LogLevel::quiet;
  throw InvalidArgument("unknown log level '" + std::string(text) + "'", {},
                        "use one of debug, info, warning, error, quiet");
}

Logger::Logger(std::ostream& out, LogLevel level) : out_(&out), level_(level) {}

void Logger::log(LogLevel level, std::string_view message) {
  if (!enabled(level) || level == LogLevel::quiet) return;
  static constexpr const char* tags[] = {"debug", "info", "warning", "error"};
  // One write per line: std::cerr is unbuffered, and piecewise writes from a manager and its
  // workers sharing a terminal interleaved ("geotandem: geotandem: info: ...").
  std::string line = "geotandem: ";
  line.append(tags[static_cast<int>(level)]).append(": ").append(message).append("\n");
  std::lock_guard lock(mutex_);
  out_->write(line.data(), static_cast<std::streamsize>(line.size()));
  out_->flush();
}

Logger& Logger::null() {
  // A function-local static holding a stream that writes nowhere: no teardown-order hazard
  // because it owns nothing but a null buffer.
  static std::ostream sink(nullptr);
  static Logger logger(sink, LogLevel::quiet);
  return logger;
}

} // namespace geotandem
