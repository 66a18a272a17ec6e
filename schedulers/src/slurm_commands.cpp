#include "geotandem/schedulers/slurm_commands.hpp"

#include <algorithm>
#include <map>
#include <sstream>

#include "job_command.hpp"

namespace geotandem::schedulers::slurm {

std::string format_walltime(long long seconds) {
  long long h = seconds / 3600, m = (seconds / 60) % 60, s = seconds % 60;
  char text[48];
  std::snprintf(text, sizeof text, "%lld:%02lld:%02lld", h, m, s);
  return text;
}

std::vector<std::string> sbatch_command(const LaunchRequest& request) {
  const bool array = request.array_size > 1;
  const std::string job = array ? "%A" : "%j";
  std::vector<std::string> argv = {"sbatch", "--parsable", "--no-requeue", "-J", request.name};
  if (!request.workdir.empty()) argv.insert(argv.end(), {"-D", request.workdir});
  if (!request.stdout_path.empty())
    argv.insert(argv.end(), {"-o", output_pattern(request.stdout_path, job, "%a", "%%")});
  if (!request.stderr_path.empty())
    argv.insert(argv.end(), {"-e", output_pattern(request.stderr_path, job, "%a", "%%")});
  if (array) argv.push_back("--array=0-" + std::to_string(request.array_size - 1));
  const Resources& r = request.resources;
  argv.insert(argv.end(), {"-n", "1", "-c", std::to_string(r.cpus)});
  if (r.memory_mb > 0) argv.push_back("--mem=" + std::to_string(r.memory_mb) + "M");
  if (r.walltime.count() > 0) argv.push_back("--time=" + format_walltime(r.walltime.count()));
  if (!r.queue.empty()) argv.insert(argv.end(), {"-p", r.queue});
  if (!r.account.empty()) argv.insert(argv.end(), {"-A", r.account});
  argv.insert(argv.end(), r.extra_args.begin(), r.extra_args.end());
  argv.insert(argv.end(), {"--wrap", job_command_line(request)});
  return argv;
}

std::optional<std::string> parse_sbatch_output(const std::string& out) {
  std::istringstream lines(out);
  std::string line;
  while (std::getline(lines, line)) {
    std::string id = line.substr(0, line.find(';'));
    while (!id.empty() && (id.back() == ' ' || id.back() == '\r'))
      id.pop_back();
    if (!id.empty() && id.find_first_not_of("0123456789") == std::string::npos) return id;
  }
  return std::nullopt;
}

std::vector<JobId> element_ids(const std::string& job_id, int array_size) {
  if (array_size <= 1) return {job_id};
  std::vector<JobId> ids;
  for (int i = 0; i < array_size; ++i)
    ids.push_back(job_id + "_" + std::to_string(i));
  return ids;
}

std::vector<std::string> squeue_command(const std::vector<JobId>& ids) {
  std::string list;
  for (const auto& id : ids)
    list += (list.empty() ? "" : ",") + id;
  return {"squeue", "-h", "-t", "all", "-r", "-j", list, "-o", "%i|%T|%r|%N"};
}

std::vector<JobReport> parse_squeue_output(const std::string& out) {
  std::vector<JobReport> reports;
  std::istringstream lines(out);
  std::string line;
  while (std::getline(lines, line)) {
    std::vector<std::string> fields;
    std::istringstream parts(line);
    std::string field;
    while (std::getline(parts, field, '|'))
      fields.push_back(field);
    if (!line.empty() && line.back() == '|') fields.emplace_back();
    if (fields.size() != 4 || fields[0].empty()) continue;
    JobReport report{fields[0], {}};
    report.status.state = state_from_slurm(fields[1]);
    if (fields[2] != "None") report.status.reason = fields[2];
    if (fields[3] != "(null)") report.status.host = fields[3];
    if (report.status.state == JobState::completed) report.status.exit_code = 0;
    reports.push_back(std::move(report));
  }
  return reports;
}

std::vector<JobId> squeue_query_ids(const std::vector<JobId>& ids) {
  std::vector<JobId> query;
  auto add = [&query](const JobId& id) {
    if (std::find(query.begin(), query.end(), id) == query.end()) query.push_back(id);
  };
  for (const auto& id : ids)
    add(id);
  for (const auto& id : ids)
    if (auto underscore = id.find('_'); underscore != std::string::npos) add(id.substr(0, underscore));
  return query;
}

std::vector<JobReport> match_reports(const std::vector<JobId>& ids, const std::vector<JobReport>& reports) {
  std::map<JobId, const JobReport*> by_id;
  for (const auto& report : reports)
    by_id[report.id] = &report;
  std::vector<JobReport> matched;
  for (const auto& id : ids) {
    auto it = by_id.find(id);
    if (it == by_id.end()) {
      auto underscore = id.find('_');
      if (underscore != std::string::npos) it = by_id.find(id.substr(0, underscore));
    }
    if (it != by_id.end()) matched.push_back(JobReport{id, it->second->status});
  }
  return matched;
}

bool squeue_reports_unknown_ids(const std::string& err) {
  return err.find("Invalid job id specified") != std::string::npos;
}

std::vector<std::string> scontrol_command(const JobId& id) {
  return {"scontrol", "show", "job", "-o", id};
}

void parse_scontrol_exit(const std::string& out, JobStatus& status) {
  // " ExitCode=3:0 " (the key is preceded by a space: DerivedExitCode= must not match).
  auto at = out.find(" ExitCode=");
  if (at == std::string::npos) return;
  int code = 0, sig = 0;
  if (std::sscanf(out.c_str() + at, " ExitCode=%d:%d", &code, &sig) != 2) return;
  status.exit_code = code;
  if (sig != 0) status.signal = sig;
}

std::vector<std::string> scancel_command(const std::vector<JobId>& ids) {
  std::vector<std::string> argv = {"scancel"};
  argv.insert(argv.end(), ids.begin(), ids.end());
  return argv;
}

JobState state_from_slurm(const std::string& state) {
  static const std::pair<const char*, JobState> table[] = {
      {"PENDING", JobState::pending},
      {"PD", JobState::pending},
      {"CONFIGURING", JobState::pending},
      {"CF", JobState::pending},
      {"REQUEUED", JobState::pending},
      {"RQ", JobState::pending},
      {"REQUEUE_HOLD", JobState::pending},
      {"REQUEUE_FED", JobState::pending},
      {"RESV_DEL_HOLD", JobState::pending},
      {"RUNNING", JobState::running},
      {"R", JobState::running},
      {"COMPLETING", JobState::running},
      {"CG", JobState::running},
      {"SUSPENDED", JobState::running},
      {"S", JobState::running},
      {"STOPPED", JobState::running},
      {"ST", JobState::running},
      {"SIGNALING", JobState::running},
      {"STAGE_OUT", JobState::running},
      {"SO", JobState::running},
      {"RESIZING", JobState::running},
      {"COMPLETED", JobState::completed},
      {"CD", JobState::completed},
      {"FAILED", JobState::failed},
      {"F", JobState::failed},
      {"OUT_OF_MEMORY", JobState::failed},
      {"OOM", JobState::failed},
      {"SPECIAL_EXIT", JobState::failed},
      {"SE", JobState::failed},
      {"CANCELLED", JobState::cancelled},
      {"CA", JobState::cancelled},
      {"PREEMPTED", JobState::cancelled},
      {"PR", JobState::cancelled},
      {"REVOKED", JobState::cancelled},
      {"RV", JobState::cancelled},
      {"TIMEOUT", JobState::timed_out},
      {"TO", JobState::timed_out},
      {"DEADLINE", JobState::timed_out},
      {"DL", JobState::timed_out},
      {"NODE_FAIL", JobState::node_failure},
      {"NF", JobState::node_failure},
      {"BOOT_FAIL", JobState::node_failure},
      {"BF", JobState::node_failure},
  };
  // "CANCELLED by 0" (older squeue) keeps only its first word.
  std::string word = state.substr(0, state.find(' '));
  for (const auto& [name, ours] : table)
    if (word == name) return ours;
  // An unknown state (a newer Slurm) is not a verdict: treat it as still running, the next known
  // state or the job's disappearance will settle it.
  return JobState::running;
}

} // namespace geotandem::schedulers::slurm
