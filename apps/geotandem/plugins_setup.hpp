#pragma once
// Builds the plugin registry a command uses: the built-in steps and attributes, added by an explicit call,
// then the shared libraries on the plugin search path.

#include "geotandem/core/log.hpp"
#include "geotandem/workflow/registry.hpp"

namespace geotandem::app {

workflow::PluginRegistry make_plugin_registry(Logger& log);

} // namespace geotandem::app
