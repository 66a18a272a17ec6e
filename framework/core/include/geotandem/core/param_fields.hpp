#pragma once
// Options structs declared as tables: one ParamField per member, its declaration (ParamSpec) and how
// the member is read as and set from a ParamValue. The extraction's options
// (tandem/extraction_options.cpp) and every built-in attribute's (attributes/params.hpp) are such
// tables, so that their parameters, defaults, codecs and checks are read from one declaration.

#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "geotandem/core/params.hpp"

namespace geotandem {

// A declaration in one call, for the tables of declarations (steps, the extraction's options, the
// recipe's sections): name, type, default (empty: required), help, closed range, choices.
ParamSpec param_spec(std::string name, ParamType type, std::optional<std::string> default_value, std::string help,
                     std::optional<double> min_value = {}, std::optional<double> max_value = {},
                     std::vector<std::string> choices = {});

template <class Struct> struct ParamField {
  ParamSpec spec;
  std::function<ParamValue(const Struct&)> get; // of the spec's type (a choice: its word)
  std::function<void(Struct&, const ParamValue&)> set;
};

// An integer, floating-point or boolean member. A float reads as the shortest decimal that reads
// back to it (0.6f is 0.6, not 0.6000000238418579), so its text and JSON are what a user wrote.
template <class Struct, class T> ParamField<Struct> member_param(ParamSpec spec, T Struct::*member) {
  static_assert(std::is_arithmetic_v<T>, "member_param: a number or a boolean; an enum is a choice_param");
  ParamField<Struct> f;
  f.spec = std::move(spec);
  f.get = [member](const Struct& s) -> ParamValue {
    const T v = s.*member;
    if constexpr (std::is_same_v<T, bool>)
      return ParamValue(v);
    else if constexpr (std::is_same_v<T, float>)
      return ParamValue(std::stod(number_text(v)));
    else if constexpr (std::is_floating_point_v<T>)
      return ParamValue(static_cast<double>(v));
    else
      return ParamValue(static_cast<std::int64_t>(v));
  };
  f.set = [member](Struct& s, const ParamValue& v) {
    if constexpr (std::is_same_v<T, bool>)
      s.*member = v.boolean;
    else if constexpr (std::is_floating_point_v<T>)
      s.*member = static_cast<T>(v.real);
    else
      s.*member = static_cast<T>(v.integer);
  };
  return f;
}

// A member (an enum, or an int) whose values 0, 1, ... are the words spec.choices. A value beyond
// them reads as its number, which check_param refuses by name.
template <class Struct, class T> ParamField<Struct> choice_param(ParamSpec spec, T Struct::*member) {
  ParamField<Struct> f;
  spec.type = ParamType::choice;
  f.spec = std::move(spec);
  f.get = [member, words = f.spec.choices](const Struct& s) {
    const auto n = static_cast<std::size_t>(s.*member);
    return ParamValue(n < words.size() ? words[n] : std::to_string(n));
  };
  f.set = [member, words = f.spec.choices](Struct& s, const ParamValue& v) {
    std::size_t n = 0;
    while (n < words.size() && words[n] != v.text)
      ++n;
    s.*member = static_cast<T>(n);
  };
  return f;
}

} // namespace geotandem
