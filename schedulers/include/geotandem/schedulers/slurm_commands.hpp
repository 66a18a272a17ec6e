#pragma once
// Slurm's command lines and output formats, as pure functions (tested without a cluster).
// Only standard client behaviour is used: the commands on PATH, SLURM_CONF from the environment.

#include <optional>
#include <string>
#include <vector>

#include "geotandem/schedulers/job_state.hpp"
#include "geotandem/schedulers/launch_request.hpp"

namespace geotandem::schedulers::slurm {

// sbatch --parsable --no-requeue -J NAME [-D DIR] [-o OUT] [-e ERR] [--array=0-(N-1)] -n 1 -c CPUS
// [--mem=NM] [--time=H:MM:SS] [-p PART] [-A ACCT] EXTRA... --wrap 'exec env K=V... ARGV...'.
// --no-requeue: the manager owns retries, and a job Slurm requeues by itself after a node failure
// would otherwise run twice.
std::vector<std::string> sbatch_command(const LaunchRequest& request);

// The job id in `sbatch --parsable` output ("4711" or "4711;cluster"); nullopt if there is none.
std::optional<std::string> parse_sbatch_output(const std::string& out);

// "4711" for one job; "4711_0" ... "4711_(N-1)" for an array.
std::vector<JobId> element_ids(const std::string& job_id, int array_size);

// The ids to ask squeue about: the given ones plus the base id of each array element ("4711" for
// "4711_2"). A pending array whose elements are cancelled before any started collapses back into
// one record that squeue shows as "4711" and no longer under "4711_2".
std::vector<JobId> squeue_query_ids(const std::vector<JobId>& ids);
// The reports for `ids`: each id's own line, or for an array element without one, its array's
// collapsed record.
std::vector<JobReport> match_reports(const std::vector<JobId>& ids, const std::vector<JobReport>& reports);

// squeue -h -t all -r -j ID,ID,... -o '%i|%T|%r|%N': every listed job, finished ones included
// (until MinJobAge), array elements one per line.
std::vector<std::string> squeue_command(const std::vector<JobId>& ids);
// Parses that output; lines that do not have the four fields are skipped.
std::vector<JobReport> parse_squeue_output(const std::string& out);
// True when squeue's failure only means "none of these ids is known any more".
bool squeue_reports_unknown_ids(const std::string& err);

// scontrol show job -o ID: used once per job that ended badly, for its exit code and signal.
std::vector<std::string> scontrol_command(const JobId& id);
// ExitCode=E:S from `scontrol show job -o` output into status (exit code, and signal when S != 0).
void parse_scontrol_exit(const std::string& out, JobStatus& status);

// scancel ID...  (exits 0 for unknown ids: cancelling is idempotent by design on Slurm's side too)
std::vector<std::string> scancel_command(const std::vector<JobId>& ids);

// Slurm's state names (PENDING, RUNNING, COMPLETED, FAILED, CANCELLED, TIMEOUT, NODE_FAIL, ...)
// and their short codes (PD, R, CD, F, CA, TO, NF, ...) to ours.
JobState state_from_slurm(const std::string& state);

// Walltime as Slurm's H:MM:SS.
std::string format_walltime(long long seconds);

} // namespace geotandem::schedulers::slurm
