#pragma once
// Parameter descriptions as data. Every attribute publishes an AttributeSpec: its name, summary,
// inputs, and its parameters in the one parameter model of geotandem (geotandem/core/params.hpp:
// name, type, default, range with open or closed ends, odd, choices, unit, help), the same
// declarations the plugin registry lists and recipes are validated against. Each options struct's
// member initialisers are its defaults; its spec() states them by reading a default-constructed
// struct, so they are stated once.

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "geotandem/core/param_fields.hpp"
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

// The options boilerplate, once for every attribute. An attribute's options struct derives from
// DeclaredOptions<Self> and defines, in its one .cpp, `static const OptionsTable<Self>& table()`:
// its name, summary, number of inputs, and one OptionField per member (option() for numbers and
// booleans, choice() for an enum whose values are its words). spec(), from_params(), to_params()
// and validate() follow; each default is read from a default-constructed struct, so it is stated
// once, in the member's initialiser.
template <class Options> using OptionField = ParamField<Options>;

template <class Options> struct OptionsTable {
  std::string name;
  std::string summary;
  int inputs = 1;
  std::vector<OptionField<Options>> fields;
};

// The shapes of parameter most attributes share: a centred window of an odd number of samples or
// traces in [lo, hi], and a Gaussian width in (0, 20] samples.
inline ParamSpec odd_window(std::string name, std::string help, double lo, double hi, std::string unit = "samples") {
  return ParamSpec{.name = std::move(name),
                   .type = ParamType::integer,
                   .help = std::move(help),
                   .min_value = lo,
                   .max_value = hi,
                   .odd = true,
                   .unit = std::move(unit)};
}
inline ParamSpec gaussian_width(std::string name, std::string help) {
  return ParamSpec{.name = std::move(name),
                   .type = ParamType::real,
                   .help = std::move(help),
                   .min_value = 0,
                   .max_value = 20,
                   .min_open = true,
                   .unit = "samples"};
}

// An int, double or bool member; an enum member whose values 0, 1, ... are its words.
template <class Options, class T> OptionField<Options> option(ParamSpec spec, T Options::*member) {
  return member_param(std::move(spec), member);
}
template <class Options, class E> OptionField<Options> choice(ParamSpec spec, E Options::*member) {
  return choice_param(std::move(spec), member);
}

template <class Options> struct DeclaredOptions {
  // The declaration: name, summary, inputs, parameters with their defaults.
  static const AttributeSpec& spec() {
    static const AttributeSpec declared = [] {
      const OptionsTable<Options>& table = Options::table();
      AttributeSpec s{table.name, table.summary, table.inputs, {}};
      const Options defaults{};
      for (const auto& f : table.fields) {
        s.params.push_back(f.spec);
        s.params.back().default_value = f.get(defaults).text;
      }
      return s;
    }();
    return declared;
  }
  // Throws InvalidArgument (see params.hpp) for unknown, mistyped or out-of-range parameters.
  static Options from_params(const ParamValues& params) {
    const ParamValues p = resolve(spec(), params);
    Options options{};
    for (const auto& f : Options::table().fields)
      f.set(options, p.at(f.spec.name));
    return options;
  }
  ParamValues to_params() const {
    ParamValues values;
    for (const auto& f : Options::table().fields)
      values[f.spec.name] = f.get(static_cast<const Options&>(*this));
    return values;
  }
  // Throws InvalidArgument naming the parameter and its valid values.
  void validate() const { resolve(spec(), to_params()); }
  // The options, validated (for an attribute's constructor).
  static const Options& validated(const Options& options) {
    options.validate();
    return options;
  }
};

} // namespace geotandem::attributes
