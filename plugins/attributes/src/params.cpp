#include "geotandem/attributes/params.hpp"

#include <stdexcept>

namespace geotandem::attributes {

const ParamSpec& AttributeSpec::param(std::string_view wanted) const {
  return find_param(params, wanted, owner());
}

std::vector<ParamSpec> with_defaults(std::vector<ParamSpec> params, const ParamValues& defaults) {
  for (auto& p : params) {
    auto found = defaults.find(p.name);
    if (found == defaults.end()) throw std::logic_error("parameter '" + p.name + "' has no default in its options");
    p.default_value = found->second.text;
  }
  return params;
}

ParamValues resolve(const AttributeSpec& spec, const ParamValues& given) {
  return resolve_params(spec.params, given, spec.owner());
}

} // namespace geotandem::attributes
