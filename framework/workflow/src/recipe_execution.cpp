// The recipe's `execution` section (recipe_execution.hpp).
#include "recipe_execution.hpp"

#include <string>

#include "geotandem/core/error.hpp"
#include "geotandem/runtime/bind_address.hpp"

namespace geotandem::workflow::detail {

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
    if (rv.count("memory")) ex.resources.memory_mb = rv.at("memory").integer;
    if (rv.count("walltime")) ex.resources.walltime_s = rv.at("walltime").integer;
    if (rv.count("queue")) ex.resources.queue = rv.at("queue").text;
    if (rv.count("account")) ex.resources.account = rv.at("account").text;
    for (const ParamValue& word : read_list(r, find_param(declared.keys, "extra_args"), declared.path))
      ex.resources.extra_args.push_back(word.text);
    r.finish(declared.key_names());
  }
  if (v.count("relay_memory")) ex.relay_memory_mb = v.at("relay_memory").integer;
  if (v.count("bind")) ex.bind = v.at("bind").text;
  try {
    (void)runtime::manager_bind_endpoint(ex.bind); // an unknown interface is an error at validation
  } catch (const InvalidArgument& e) {
    throw error_at(m.source(), m.node("bind"), e.message(), e.hint());
  }
  m.finish(section.key_names());
}

} // namespace geotandem::workflow::detail
