#pragma once
// A worker near the end of its job's walltime stops taking tasks: it finishes the task in hand,
// tells the manager it retires (RETIRE), hands its surface to another worker when told to (SEND)
// and leaves when told FINISHED, so that the scheduler never kills it in the middle of a task; the
// manager starts a replacement job (with a fresh walltime). A retiring worker still waiting for
// someone to take its surface when half the margin is left leaves anyway (its leaves are re-done). The walltime comes
// from the job's environment: GEOTANDEM_WALLTIME_SECONDS, which the scheduler launcher exports when the run asks for
// one (execution.resources.walltime), counted from the worker's start.
#include <string>

namespace geotandem::runtime::detail {

inline constexpr const char* walltime_variable = "GEOTANDEM_WALLTIME_SECONDS";
// Seconds before the walltime at which a worker stops taking tasks (default: walltime_margin()).
// Tests set it.
inline constexpr const char* walltime_margin_variable = "GEOTANDEM_WALLTIME_MARGIN_SECONDS";

// The default margin for a walltime of `walltime` seconds: 5 % of it, at least 60 s and at most
// 10 minutes, but never more than a quarter of the walltime (a job of a few minutes on a test
// queue still works three quarters of its time instead of retiring after its first task).
double walltime_margin(double walltime);

// Empty while the worker may take another task; otherwise why it must stop ("2 s left of its
// 60 s walltime ..."). Without a walltime in the environment: always empty.
std::string walltime_exhausted();
// True once less than half the margin is left: a retiring worker stops waiting and leaves.
bool walltime_nearly_over();

} // namespace geotandem::runtime::detail
