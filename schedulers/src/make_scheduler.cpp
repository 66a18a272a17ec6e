#include "geotandem/schedulers/make_scheduler.hpp"

#include "geotandem/schedulers/local_scheduler.hpp"
#include "geotandem/schedulers/lsf_scheduler.hpp"
#include "geotandem/schedulers/slurm_scheduler.hpp"

namespace geotandem::schedulers {

std::unique_ptr<Scheduler> make_scheduler(const std::string& name, SchedulerOptions options) {
  if (name == "local") return std::make_unique<LocalScheduler>(std::move(options));
  if (name == "slurm") return std::make_unique<SlurmScheduler>(std::move(options));
  if (name == "lsf") return std::make_unique<LsfScheduler>(std::move(options));
  throw InvalidArgument("unknown scheduler '" + name + "'", {}, "use local, slurm or lsf");
}

} // namespace geotandem::schedulers
