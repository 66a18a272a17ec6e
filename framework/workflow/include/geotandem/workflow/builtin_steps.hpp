#pragma once
// The steps the workflow library provides itself, as plugins like any other: extract,
// remove_bubbles, sort_by_azimuth, export and report. Added to a registry by an explicit call.

#include "geotandem/workflow/registry.hpp"

namespace geotandem::workflow {

// The version built-in steps and attributes report.
inline constexpr const char* builtin_version = "0.1.0";

// Adds extract, remove_bubbles, sort_by_azimuth, export and report. Throws InvalidArgument if a
// step of the same name is already registered.
void register_builtin_steps(PluginRegistry& registry);

} // namespace geotandem::workflow
