#include "geotandem/schedulers/scheduler_error.hpp"

namespace geotandem::schedulers {

namespace {
std::string trimmed(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ' || text.back() == '\r'))
    text.pop_back();
  constexpr std::size_t limit = 2000;
  if (text.size() > limit) text = text.substr(0, limit) + " [...]";
  return text;
}
} // namespace

SchedulerError::SchedulerError(const std::string& backend, const std::string& message, const std::string& hint)
    : Error(std::string(backend).append(": ").append(message), {}, hint), backend_(backend) {}

SchedulerError command_failed(const std::string& backend, const std::vector<std::string>& argv,
                              const CommandResult& result, const std::string& hint) {
  std::string command = "`";
  command.append(describe_command(argv)).append("`");
  const std::string program = argv.empty() ? std::string("the command") : argv.front();
  if (!result.spawn_error.empty()) {
    return SchedulerError(backend, command + " could not be started: " + result.spawn_error,
                          hint.empty() ? "is '" + program + "' installed and on PATH on this machine?" : hint);
  }
  if (result.timed_out) {
    return SchedulerError(backend,
                          command + " hung and was killed after its timeout" +
                              (result.err.empty() ? std::string() : "; it had printed: " + trimmed(result.err)),
                          hint.empty() ? "the scheduler's controller may be down or overloaded; check it with its "
                                         "own tools, or raise the scheduler command timeout"
                                       : hint);
  }
  std::string how = result.signal != 0 ? "was killed by signal " + std::to_string(result.signal)
                                       : "failed (exit " + std::to_string(result.exit_code) + ")";
  std::string said = trimmed(result.err.empty() ? result.out : result.err);
  return SchedulerError(backend, command + " " + how + (said.empty() ? std::string() : ": " + said), hint);
}

} // namespace geotandem::schedulers
