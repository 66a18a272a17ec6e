#include "geotandem/schedulers/lsf_commands.hpp"

#include <regex>
#include <sstream>

#include "job_command.hpp"

namespace geotandem::schedulers::lsf {

std::string format_walltime(long long seconds) {
  long long minutes = (seconds + 59) / 60;
  char text[48];
  std::snprintf(text, sizeof text, "%lld:%02lld", minutes / 60, minutes % 60);
  return text;
}

std::vector<std::string> bsub_command(const LaunchRequest& request) {
  const bool array = request.array_size > 1;
  std::string name = request.name;
  if (array) name += "[1-" + std::to_string(request.array_size) + "]";
  const Resources& r = request.resources;
  std::vector<std::string> argv = {"bsub", "-J", name, "-n", std::to_string(r.cpus), "-R", "span[hosts=1]"};
  if (!r.queue.empty()) argv.insert(argv.end(), {"-q", r.queue});
  if (r.walltime.count() > 0) argv.insert(argv.end(), {"-W", format_walltime(r.walltime.count())});
  if (!request.stdout_path.empty())
    argv.insert(argv.end(), {"-o", output_pattern(request.stdout_path, "%J", "%I", "%")});
  if (!request.stderr_path.empty())
    argv.insert(argv.end(), {"-e", output_pattern(request.stderr_path, "%J", "%I", "%")});
  if (!r.account.empty()) argv.insert(argv.end(), {"-P", r.account});
  if (r.memory_mb > 0) argv.insert(argv.end(), {"-M", std::to_string(r.memory_mb) + "MB"});
  if (!request.workdir.empty()) argv.insert(argv.end(), {"-cwd", request.workdir});
  argv.insert(argv.end(), r.extra_args.begin(), r.extra_args.end());
  argv.push_back(job_command_line(request));
  return argv;
}

std::optional<std::string> parse_bsub_output(const std::string& out) {
  static const std::regex submitted(R"(Job <([0-9]+)> is submitted to (default )?queue <[^>]*>)");
  std::smatch match;
  if (std::regex_search(out, match, submitted)) return match[1].str();
  return std::nullopt;
}

std::vector<JobId> element_ids(const std::string& job_id, int array_size) {
  if (array_size <= 1) return {job_id};
  std::vector<JobId> ids;
  for (int i = 1; i <= array_size; ++i)
    ids.push_back(job_id + "[" + std::to_string(i) + "]");
  return ids;
}

std::vector<std::string> bjobs_command(const std::vector<JobId>& ids) {
  std::vector<std::string> argv = {"bjobs", "-noheader", "-o", bjobs_format};
  argv.insert(argv.end(), ids.begin(), ids.end());
  return argv;
}

namespace {
std::string trim(std::string text) {
  auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}
bool all_digits(const std::string& text) {
  return !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
}
} // namespace

std::vector<JobReport> parse_bjobs_output(const std::string& out) {
  std::vector<JobReport> reports;
  std::istringstream lines(out);
  std::string line;
  while (std::getline(lines, line)) {
    std::vector<std::string> fields;
    std::size_t start = 0;
    for (;;) {
      auto end = line.find('^', start);
      fields.push_back(trim(line.substr(start, end == std::string::npos ? std::string::npos : end - start)));
      if (end == std::string::npos) break;
      start = end + 1;
    }
    if (fields.size() != 5) continue; // "Job <7> is not found", warnings, blank lines
    std::string id = fields[0];
    // With LSB_BJOBS_DISPLAY_ENH=Y the jobid column already reads "4711[3]".
    if (auto bracket = id.find('['); bracket != std::string::npos) {
      if (!all_digits(id.substr(0, bracket))) continue;
    } else {
      if (!all_digits(id)) continue;
      if (all_digits(fields[1]) && fields[1] != "0") id += "[" + fields[1] + "]";
    }
    JobReport report{id, {}};
    report.status.state = state_from_lsf(fields[2]);
    if (all_digits(fields[3]))
      report.status.exit_code = std::stoi(fields[3]);
    else if (report.status.state == JobState::completed)
      report.status.exit_code = 0;
    if (fields[4] != "-") report.status.host = fields[4];
    if (report.status.state == JobState::pending || report.status.state == JobState::running) {
      if (fields[2] != "PEND" && fields[2] != "RUN") report.status.reason = "LSF state " + fields[2];
    }
    if (fields[2] == "UNKWN" || fields[2] == "ZOMBI")
      report.status.reason = "LSF state " + fields[2] + ": the execution host is unreachable or the job was lost";
    reports.push_back(std::move(report));
  }
  return reports;
}

std::vector<std::string> bkill_command(const std::vector<JobId>& ids) {
  std::vector<std::string> argv = {"bkill"};
  argv.insert(argv.end(), ids.begin(), ids.end());
  return argv;
}

bool bkill_reports_finished(const std::string& text) {
  // Every complaint line must be about a finished or unknown job.
  std::istringstream lines(text);
  std::string line;
  bool any = false;
  while (std::getline(lines, line)) {
    if (trim(line).empty()) continue;
    if (line.find("is being terminated") != std::string::npos || line.find("is being signaled") != std::string::npos)
      continue;
    if (line.find("Job has already finished") != std::string::npos ||
        line.find("No matching job found") != std::string::npos || line.find("is not found") != std::string::npos) {
      any = true;
      continue;
    }
    return false;
  }
  return any;
}

JobState state_from_lsf(const std::string& stat) {
  if (stat == "PEND" || stat == "PSUSP" || stat == "WAIT" || stat == "PROV") return JobState::pending;
  if (stat == "RUN" || stat == "USUSP" || stat == "SSUSP") return JobState::running;
  if (stat == "DONE") return JobState::completed;
  if (stat == "EXIT") return JobState::failed;
  if (stat == "UNKWN" || stat == "ZOMBI") return JobState::node_failure;
  return JobState::running; // an unknown word is not a verdict
}

} // namespace geotandem::schedulers::lsf
