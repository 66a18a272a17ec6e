#include "job_command.hpp"

#include "posix_spawn_util.hpp"

namespace geotandem::schedulers {

std::string job_command_line(const LaunchRequest& request) {
  std::string line = "exec env";
  if (!request.token.empty()) line += " " + shell_quote(std::string(launch_token_variable) + "=" + request.token);
  for (const auto& [key, value] : request.env)
    line += " " + shell_quote(key + "=" + value);
  for (const auto& arg : request.argv)
    line += " " + shell_quote(arg);
  return line;
}

std::string output_pattern(const std::string& path, const std::string& job_token, const std::string& index_token,
                           const std::string& percent_escape) {
  std::string result;
  for (std::size_t i = 0; i < path.size();) {
    if (path.compare(i, 5, "{job}") == 0) {
      result += job_token;
      i += 5;
    } else if (path.compare(i, 7, "{index}") == 0) {
      result += index_token;
      i += 7;
    } else if (path[i] == '%') {
      result += percent_escape;
      ++i;
    } else {
      result += path[i++];
    }
  }
  return result;
}

} // namespace geotandem::schedulers
