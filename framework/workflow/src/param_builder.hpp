#pragma once
// A parameter declaration in one call, for the built-in steps' tables (builtin_steps.cpp): core's
// param_spec() (geotandem/core/params.hpp).

#include "geotandem/core/param_fields.hpp"
#include "geotandem/workflow/plugin.hpp"

namespace geotandem::workflow::detail {

using geotandem::param_spec;

} // namespace geotandem::workflow::detail
