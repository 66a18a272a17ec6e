#pragma once
// The scheduler backends, as a table like the steps' registry: a recipe's `execution.scheduler`,
// `--scheduler`, `geotandem validate` and docs/recipe-schema.md read their names from it, and
// make_scheduler() builds one by name. This table is the only list of the names.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "geotandem/schedulers/scheduler.hpp"

namespace geotandem::schedulers {

struct SchedulerBackend {
  std::string name;    // as recipes spell it
  std::string summary; // one line, for help and docs
  std::function<std::unique_ptr<Scheduler>(SchedulerOptions)> make;
};

// local, slurm, lsf: in that order.
const std::vector<SchedulerBackend>& scheduler_backends();
// Their names, in the same order.
std::vector<std::string> scheduler_names();

// The backend called `name`; anything else is an InvalidArgument that lists the names, with the
// nearest one.
std::unique_ptr<Scheduler> make_scheduler(const std::string& name, SchedulerOptions options = {});

} // namespace geotandem::schedulers
