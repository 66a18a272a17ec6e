#include "geotandem/schedulers/make_scheduler.hpp"

#include "geotandem/core/error.hpp"
#include "geotandem/core/suggest.hpp"
#include "geotandem/schedulers/local_scheduler.hpp"
#include "geotandem/schedulers/lsf_scheduler.hpp"
#include "geotandem/schedulers/slurm_scheduler.hpp"

namespace geotandem::schedulers {
namespace {

template <class Backend> std::function<std::unique_ptr<Scheduler>(SchedulerOptions)> maker() {
  return [](SchedulerOptions options) { return std::make_unique<Backend>(std::move(options)); };
}

} // namespace

const std::vector<SchedulerBackend>& scheduler_backends() {
  static const std::vector<SchedulerBackend> backends = {
      {"local", "child processes of this machine", maker<LocalScheduler>()},
      {"slurm", "one Slurm job per worker", maker<SlurmScheduler>()},
      {"lsf", "one LSF job per worker", maker<LsfScheduler>()},
  };
  return backends;
}

std::vector<std::string> scheduler_names() {
  std::vector<std::string> names;
  for (const auto& b : scheduler_backends())
    names.push_back(b.name);
  return names;
}

std::unique_ptr<Scheduler> make_scheduler(const std::string& name, SchedulerOptions options) {
  for (const auto& b : scheduler_backends())
    if (b.name == name) return b.make(std::move(options));
  throw InvalidArgument("unknown scheduler '" + name + "'", {}, suggestion_hint(name, scheduler_names()));
}

} // namespace geotandem::schedulers
