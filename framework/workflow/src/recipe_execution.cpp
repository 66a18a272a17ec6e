// The recipe's `execution` section (recipe_execution.hpp).
#include "recipe_execution.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>

#include "geotandem/core/error.hpp"
#include "geotandem/runtime/bind_address.hpp"

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
  const RecipeSection& section = recipe_section("execution");
  const ParamValues v = read_section(m, section);
  ex.scheduler = v.at("scheduler").text; // one of the scheduler backends' names (schedulers::scheduler_backends)
  ex.workers_given = v.count("workers") > 0;
  if (ex.workers_given) ex.workers = static_cast<int>(v.at("workers").integer);
  if (m.has("resources")) {
    const RecipeSection& declared = recipe_section("execution.resources");
    MapReader r(m.source(), m.node("resources"), declared.path);
    const ParamValues rv = read_section(r, declared);
    ex.resources.cpus_per_worker = static_cast<int>(rv.at("cpus_per_worker").integer);
    if (rv.count("memory")) ex.resources.memory_mb = parse_memory(m.source(), r.node("memory"), rv.at("memory").text);
    if (rv.count("walltime"))
      ex.resources.walltime_s = parse_walltime(m.source(), r.node("walltime"), rv.at("walltime").text);
    if (rv.count("queue")) ex.resources.queue = rv.at("queue").text;
    if (rv.count("account")) ex.resources.account = rv.at("account").text;
    ex.resources.extra_args = r.text_list("extra_args");
    r.finish(declared.key_names());
  }
  if (v.count("relay_memory"))
    ex.relay_memory_mb = parse_memory(m.source(), m.node("relay_memory"), v.at("relay_memory").text, true);
  if (v.count("bind")) ex.bind = v.at("bind").text;
  try {
    (void)runtime::manager_bind_endpoint(ex.bind); // an unknown interface is an error at validation
  } catch (const InvalidArgument& e) {
    throw error_at(m.source(), m.node("bind"), e.message(), e.hint());
  }
  m.finish(section.key_names());
}

} // namespace geotandem::workflow::detail
