#pragma once
// The backend for a recipe's `execution.scheduler` / `--scheduler` name.

#include <memory>
#include <string>

#include "geotandem/schedulers/scheduler.hpp"

namespace geotandem::schedulers {

// "local", "slurm" or "lsf"; anything else is an InvalidArgument that lists the three.
std::unique_ptr<Scheduler> make_scheduler(const std::string& name, SchedulerOptions options = {});

} // namespace geotandem::schedulers
