#pragma once
// "Did you mean ...?" for unknown keys and names: core's (geotandem/core/suggest.hpp), which the
// parameter model uses too.

#include "geotandem/core/suggest.hpp"

namespace geotandem::workflow {

using geotandem::edit_distance;
using geotandem::nearest;
using geotandem::suggestion_hint;

} // namespace geotandem::workflow
