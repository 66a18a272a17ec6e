#pragma once
// The built-in attributes as data: one table of factories (catalog.cpp), each row an attribute's
// declaration, check and factory, for the recipe and plugin layers. Nothing registers itself; the
// table is the whole catalogue: adding an attribute is its one file and one row there.

#include <memory>
#include <string_view>
#include <vector>

#include "geotandem/attributes/attribute.hpp"
#include "geotandem/attributes/params.hpp"

namespace geotandem::attributes {

// envelope, rms, semblance, chaos, normalise, product: in that order.
const std::vector<AttributeSpec>& builtin_attributes();

// Checks `params` for the attribute `name` as building it would (every parameter against its
// declaration, then the options' own validate()), without inputs. Throws InvalidArgument as
// make_attribute does.
void check_params(std::string_view name, const ParamValues& params);

// Builds the attribute `name` over `inputs` with `params` (given by a recipe, possibly partial:
// missing parameters take their defaults). Throws InvalidArgument for an unknown name (listing the
// known ones), a wrong number of inputs, or unknown, mistyped or out-of-range parameters.
std::shared_ptr<Attribute> make_attribute(std::string_view name, std::vector<VolumePtr> inputs,
                                          const ParamValues& params = {});

} // namespace geotandem::attributes
