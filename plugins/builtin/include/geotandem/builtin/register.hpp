#pragma once
// The built-in attribute plugins, added to a registry by an explicit call from main (no static
// registration). They behave exactly like shared-library plugins: described parameters, validated
// values, lazy volumes computed box by box.

#include "geotandem/workflow/registry.hpp"

namespace geotandem::builtin {

// Adds envelope, rms, chaos, semblance, normalise and product. Throws InvalidArgument if a plugin of
// the same name is already registered.
void register_attributes(workflow::PluginRegistry& registry);

// Every built-in step: the attributes above and the workflow's own steps (extract,
// remove_bubbles, sort_by_azimuth, export, report).
void register_builtins(workflow::PluginRegistry& registry);

} // namespace geotandem::builtin
