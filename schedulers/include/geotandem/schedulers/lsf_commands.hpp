#pragma once
// IBM Spectrum LSF's command lines and output formats, as pure functions. Written from IBM's
// documentation; never run against a real LSF (none can be installed here): see
// schedulers/README.md for exactly what was tried.

#include <optional>
#include <string>
#include <vector>

#include "geotandem/schedulers/job_state.hpp"
#include "geotandem/schedulers/launch_request.hpp"

namespace geotandem::schedulers::lsf {

// bsub -J NAME | -J "NAME[1-N]" -n CPUS -R "span[hosts=1]" [-q Q] [-W H:MM] [-o OUT] [-e ERR]
// [-P PROJECT] [-M NMB] [-cwd DIR] EXTRA... 'exec env K=V... ARGV...'
// The command goes as one argument: LSF writes it into the job's script, which a shell runs.
std::vector<std::string> bsub_command(const LaunchRequest& request);

// The id in "Job <4711> is submitted to queue <normal>." (or "... to default queue <normal>.").
std::optional<std::string> parse_bsub_output(const std::string& out);

// "4711" for one job; "4711[1]" ... "4711[N]" for an array (LSF's indices start at 1).
std::vector<JobId> element_ids(const std::string& job_id, int array_size);

// The output format: fields separated by '^' so that host lists with spaces survive.
inline constexpr const char* bjobs_format = "jobid jobindex stat exit_code exec_host delimiter='^'";
// bjobs -noheader -o FORMAT ID...
std::vector<std::string> bjobs_command(const std::vector<JobId>& ids);
// Parses bjobs output. bjobs exits non-zero when one id is unknown yet prints valid lines for the
// others; "Job <N> is not found" lines and anything malformed are skipped.
std::vector<JobReport> parse_bjobs_output(const std::string& out);

// bkill ID...
std::vector<std::string> bkill_command(const std::vector<JobId>& ids);
// True when bkill's complaint only concerns jobs that are finished or unknown.
bool bkill_reports_finished(const std::string& text);

// PEND, PSUSP, RUN, USUSP, SSUSP, DONE, EXIT, UNKWN, ZOMBI, WAIT, PROV to ours.
JobState state_from_lsf(const std::string& stat);

// Walltime as LSF's -W [hours:]minutes, rounded up to a whole minute.
std::string format_walltime(long long seconds);

} // namespace geotandem::schedulers::lsf
