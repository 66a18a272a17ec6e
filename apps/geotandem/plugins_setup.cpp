#include "plugins_setup.hpp"

#include "geotandem/builtin/register.hpp"

namespace geotandem::app {

workflow::PluginRegistry make_plugin_registry(Logger& log) {
  workflow::PluginRegistry registry;
  builtin::register_builtins(registry);
  registry.discover(workflow::PluginRegistry::default_search_path(), log);
  return registry;
}

} // namespace geotandem::app
