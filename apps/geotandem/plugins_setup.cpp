#include "plugins_setup.hpp"

#include "geotandem/builtin/register.hpp"
#ifdef GEOTANDEM_PYTHON_STEP
#include "geotandem/python_step/register.hpp"
#endif

namespace geotandem::app {

workflow::PluginRegistry make_plugin_registry(Logger& log) {
  workflow::PluginRegistry registry;
  builtin::register_builtins(registry);
#ifdef GEOTANDEM_PYTHON_STEP
  python_step::register_python_step(registry); // attributes written in Python (built with GEOTANDEM_PYTHON_STEP)
#endif
  registry.discover(workflow::PluginRegistry::default_search_path(), log);
  return registry;
}

} // namespace geotandem::app
