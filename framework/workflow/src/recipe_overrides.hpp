#pragma once
// --set overrides of a recipe: "dotted.path=value" applied to the YAML tree before validation.

#include <string>

#include <yaml-cpp/yaml.h>

namespace geotandem::workflow::detail {

// Applies one --set override to the YAML tree. Steps are addressed by index (steps.2.iso) or by
// their 'as' / step name (steps.extract.iso). Throws InvalidArgument for a malformed override or
// an unknown step. Returns the nodes it put in the tree: the value (its positions are within the
// value) and, in a mapping, its key (which has none).
struct GraftedOverride {
  YAML::Node key; // null when the value replaced a step of the list
  YAML::Node value;
};
GraftedOverride apply_override(YAML::Node root, const std::string& text);

} // namespace geotandem::workflow::detail
