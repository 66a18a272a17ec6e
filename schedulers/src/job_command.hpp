#pragma once
// What the batch backends hand to the scheduler's shell: the request's argv, with its environment
// and launch token, as one line of POSIX shell text.

#include <string>

#include "geotandem/schedulers/launch_request.hpp"

namespace geotandem::schedulers {

// "exec env 'GEOTANDEM_LAUNCH_TOKEN=t' 'K=V' 'prog' 'arg 1'": every word single-quoted, so nothing
// in argv or env is interpreted by the job's shell. `exec` leaves no shell between the scheduler
// and the program (signals such as scancel's SIGTERM reach it directly).
std::string job_command_line(const LaunchRequest& request);

// Replaces "{job}" and "{index}" in an output path with the scheduler's own patterns and escapes
// the scheduler's pattern character elsewhere (Slurm: "%%"; LSF has no escape, '%' stays).
std::string output_pattern(const std::string& path, const std::string& job_token, const std::string& index_token,
                           const std::string& percent_escape);

} // namespace geotandem::schedulers
