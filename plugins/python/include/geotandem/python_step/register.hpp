#pragma once
// The `python` step: an attribute computed by a Python function (docs/plugins.md, "Attributes
// written in Python"). Added to a registry by an explicit call, like the built-ins.
//
// The library uses the Python C API of the process it runs in and does not link libpython itself:
// an executable that registers the step links it (geotandem links Python3::Python and embeds an
// interpreter on first use); an extension module loaded by python3 finds it in its host.

#include "geotandem/workflow/registry.hpp"

namespace geotandem::python_step {

// Adds the step `python`. Throws InvalidArgument if a step of that name is already registered.
void register_python_step(workflow::PluginRegistry& registry);

} // namespace geotandem::python_step
