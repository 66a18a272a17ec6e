// The recipe's `execution` section (recipe_execution.hpp).
#include "recipe_execution.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>

#include "geotandem/core/error.hpp"
#include "geotandem/runtime/bind_address.hpp"
#include "geotandem/workflow/suggest.hpp"

namespace geotandem::workflow::detail {
namespace {

std::int64_t parse_walltime(const RecipeSource& source, const YAML::Node& node, const std::string& text) {
  // [[hh:]mm:]ss or a plain number of minutes
  int h = 0, mi = 0, s = 0;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%d:%d:%d%c", &h, &mi, &s, &extra) == 3) return h * 3600 + mi * 60 + s;
  if (std::sscanf(text.c_str(), "%d:%d%c", &h, &mi, &extra) == 2) return h * 3600 + mi * 60;
  if (std::sscanf(text.c_str(), "%d%c", &mi, &extra) == 1 && mi > 0) return mi * 60;
  throw error_at(source, node, "walltime '" + text + "' is not hh:mm:ss, hh:mm or minutes");
}

// A size in MiB: "2048M", "4G", a plain number of MiB; 0 only when `zero_allowed`.
std::int64_t parse_memory(const RecipeSource& source, const YAML::Node& node, const std::string& text,
                          bool zero_allowed = false) {
  char* end = nullptr;
  double v = std::strtod(text.c_str(), &end);
  std::string unit = end ? end : "";
  double mb = unit == "" || unit == "M" || unit == "MB" ? v : unit == "G" || unit == "GB" ? v * 1024 : -1;
  if (!(v > 0 || (zero_allowed && v == 0)) || mb < 0 || end == text.c_str())
    throw error_at(source, node,
                   "memory '" + text + "' is not a size like 2048M or 4G" + (zero_allowed ? " (or 0)" : ""));
  return static_cast<std::int64_t>(mb);
}

} // namespace

void parse_execution(MapReader& m, ExecutionSpec& ex) {
  ex.scheduler = m.text("scheduler", "local");
  if (ex.scheduler != "local" && ex.scheduler != "slurm" && ex.scheduler != "lsf")
    throw error_at(m.source(), m.node("scheduler"), "unknown scheduler '" + ex.scheduler + "'",
                   suggestion_hint(ex.scheduler, {"local", "slurm", "lsf"}));
  ex.workers_given = m.has("workers");
  ex.workers = static_cast<int>(m.integer("workers", 1, 1, 4096));
  if (m.has("resources")) {
    MapReader r(m.source(), m.node("resources"), "execution.resources");
    ex.resources.cpus_per_worker = static_cast<int>(r.integer("cpus_per_worker", 1, 1, 1024));
    if (r.has("memory")) {
      YAML::Node n = r.node("memory");
      ex.resources.memory_mb = parse_memory(m.source(), n, detail::scalar_of(m.source(), n, "memory"));
    }
    if (r.has("walltime")) {
      YAML::Node n = r.node("walltime");
      ex.resources.walltime_s = parse_walltime(m.source(), n, detail::scalar_of(m.source(), n, "walltime"));
    }
    ex.resources.queue = r.text("queue", "");
    ex.resources.account = r.text("account", "");
    ex.resources.extra_args = r.text_list("extra_args");
    r.finish({"cpus_per_worker", "memory", "walltime", "queue", "account", "extra_args"});
  }
  if (m.has("relay_memory")) {
    YAML::Node n = m.node("relay_memory");
    ex.relay_memory_mb = parse_memory(m.source(), n, detail::scalar_of(m.source(), n, "relay_memory"), true);
  }
  ex.bind = m.text("bind", "");
  try {
    (void)runtime::manager_bind_endpoint(ex.bind); // an unknown interface is an error at validation
  } catch (const InvalidArgument& e) {
    throw error_at(m.source(), m.node("bind"), e.message(), e.hint());
  }
  m.finish({"scheduler", "workers", "resources", "bind", "relay_memory"});
}

} // namespace geotandem::workflow::detail
