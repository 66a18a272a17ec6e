#pragma once
// Parameter descriptions as data. Every attribute publishes an AttributeSpec: its name, summary,
// inputs, and its parameters in the one parameter model of geotandem (geotandem/core/params.hpp:
// name, type, default, range with open or closed ends, odd, choices, unit, help), the same
// declarations the plugin registry lists and recipes are validated against. Each options struct's
// member initialisers are its defaults; its spec() states them by reading a default-constructed
// struct, so they are stated once.

#include <string>
#include <string_view>
#include <vector>

#include "geotandem/core/params.hpp"

namespace geotandem::attributes {

using geotandem::number_text;
using geotandem::ParamSpec;
using geotandem::ParamType;
using geotandem::ParamValue;
using geotandem::ParamValues;
using geotandem::to_string;

struct AttributeSpec {
  std::string name;
  std::string summary;
  int inputs = 1; // number of input volumes
  std::vector<ParamSpec> params;

  // The parameter called `name`; throws InvalidArgument listing the known ones otherwise.
  const ParamSpec& param(std::string_view name) const;
  // "attribute 'chaos'": how messages name it.
  std::string owner() const { return "attribute '" + name + "'"; }
};

// `params` with each default set to the text of its value in `defaults` (the options struct's
// to_params() of a default-constructed struct), so that a default is stated once, in the struct's
// member initialiser. Throws std::logic_error if a parameter has no value in `defaults`.
std::vector<ParamSpec> with_defaults(std::vector<ParamSpec> params, const ParamValues& defaults);

// Checks `given` (possibly partial) against `spec` and returns every parameter, defaults filled in,
// each of its declared type (an integer is accepted for a real). Throws InvalidArgument naming the
// attribute and the parameter for an unknown name (listing the known ones), a wrong type, or a
// value outside the valid values (geotandem::resolve_params).
ParamValues resolve(const AttributeSpec& spec, const ParamValues& given);

} // namespace geotandem::attributes
