#pragma once
// The recipe's `execution` section (docs/recipe-schema.md): where the extraction's workers run,
// how many, with which resources, and the address the manager listens on.
#include "geotandem/workflow/recipe.hpp"
#include "yaml_reader.hpp"

namespace geotandem::workflow::detail {

// Reads the section into `ex`; every error names the recipe's file, line and column.
void parse_execution(MapReader& m, ExecutionSpec& ex);

} // namespace geotandem::workflow::detail
