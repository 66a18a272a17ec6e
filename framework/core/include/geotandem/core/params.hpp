#pragma once
// The one parameter model. Every step declares its parameters as ParamSpecs: the built-in
// attributes (plugins/attributes), the workflow's own steps (framework/workflow), and plugins
// through the C ABI (gt_param_spec in plugin_abi.h is this struct's C form, mapped in
// abi_plugin.cpp). Recipes, the command line and C++ callers give values; the functions below
// check them against the declaration with the same messages wherever they come from.

#include <concepts>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace geotandem {

enum class ParamType { integer, real, boolean, text, choice };
// "integer", "real", "boolean", "text", "choice".
const char* to_string(ParamType type);

// A declared parameter.
struct ParamSpec {
  std::string name;
  ParamType type = ParamType::real;
  std::optional<std::string> default_value; // as a recipe writes it; empty: required
  std::string help;                         // one sentence
  std::optional<double> min_value;          // integer and real; inclusive unless min_open
  std::optional<double> max_value;          // inclusive unless max_open
  std::vector<std::string> choices;         // choice: the accepted words
  bool min_open = false;
  bool max_open = false;
  bool odd = false; // integers that must be odd (centred window lengths)
  std::string unit; // "samples", "traces", "percent", ...; empty when there is none
  // Text parameters only. `list`: a recipe may write the value as a YAML list of scalars
  // ([1, 1, 8]); its text is then "[1, 1, 8]" and the step's check() reads it. `recipe_path`: a
  // path relative to the recipe's directory, made absolute when the recipe is read, so that the
  // chain description carries it to workers that run elsewhere.
  bool list = false;
  bool recipe_path = false;
  // A list's entries: their type (the spec's range, odd and choices apply to each entry) and, when
  // not 0, how many there must be. A list of 3 integers in [16, 100000]: a cube's shape.
  ParamType item_type = ParamType::text;
  std::size_t list_length = 0;
  bool table_items = false; // entries are tables the caller reads (each export's parameters)
  // A text parameter written in a unit of its own, read into ParamValue::integer: a size in MiB
  // ("2048M", "4G", a plain number of MiB) or a duration in seconds ("hh:mm:ss", "hh:mm", minutes).
  // The spec's range applies to that integer.
  enum class Form { plain, size_mib, duration_s };
  Form form = Form::plain;
  // A real used as a 32-bit float (an isovalue compared with float samples, a divisor of them): a
  // value beyond the float range (|value| > 3.4028235e38) is refused by name instead of becoming
  // infinity, and one that is not 0 but would round to 0 (|value| < 1.4e-45) instead of becoming 0.
  bool single_precision = false;

  // Whether `value` lies in the declared interval (NaN never does).
  bool in_range(double value) const;
  // The declaration of one entry of this list: the same name, range and choices, of type item_type.
  ParamSpec entry() const;
  // The interval with its open and closed ends: "[1, 1001]", "(0, 20]", "(0, inf)".
  std::string range_text() const;
  // What the parameter accepts, for messages: "an odd integer in [1, 1001]", "a real in (0, 20]",
  // "one of planarity, marfurt", "true or false", "an integer", "text".
  std::string valid_values() const;
};

// A parameter value: as given (a recipe's text parsed, or a typed C++ value), and after checking
// against its spec, of the spec's type. `text` is the value as written: the recipe's own text, or
// the shortest text that reads back to a C++ value ("9", "2.5", "planarity").
struct ParamValue {
  ParamType type = ParamType::text;
  std::int64_t integer = 0; // integer (and the integer's value as `real`)
  double real = 0.0;        // real
  bool boolean = false;     // boolean
  std::string text;         // every type; the word of text and choice

  ParamValue() = default;
  template <std::integral T>
  requires(!std::same_as<T, bool>) ParamValue(T value) : ParamValue(integer_value(static_cast<std::int64_t>(value))) {}
  ParamValue(double value);
  ParamValue(bool value);
  ParamValue(std::string word);
  ParamValue(const char* word) : ParamValue(std::string(word)) {}

  // Same type and same value of that type (a real's text "1.0" equals "1"; a choice equals the same
  // word as text).
  friend bool operator==(const ParamValue& a, const ParamValue& b);

private:
  static ParamValue integer_value(std::int64_t value);
};

// Parameters by name: as given (possibly partial) or resolved (every declared one).
using ParamValues = std::map<std::string, ParamValue, std::less<>>;

// The shortest text that reads back to `value` ("2", "0.5", "1e+30", "inf").
std::string number_text(double value);
// The same for a float, such as a sample's value: -999.25, 1.1 (not the double 1.100000023841858).
std::string number_text(float value);
// "name=value, name=value" in the map's order, for messages and descriptions.
std::string to_string(const ParamValues& values);

// Every error below is an InvalidArgument whose message names the parameter, the value and what is
// allowed, prefixed by `owner` when given ("attribute 'chaos': parameter 'sigma_g' is 0, out of
// range: it must be a real in (0, 20]"), with a hint (the range in words, the nearest choice, the
// odd neighbours, or the parameter's help).

// Parses `text` (a recipe value or a default) for `spec` and checks it.
ParamValue parse_param(const ParamSpec& spec, const std::string& text, std::string_view owner = {});
// Checks a typed value against `spec` and returns it as the spec's type: an integer is accepted for
// a real, and a word for a choice.
ParamValue check_param(const ParamSpec& spec, const ParamValue& value, std::string_view owner = {});

// The declaration called `name`; throws InvalidArgument listing the known names (with the nearest).
const ParamSpec& find_param(const std::vector<ParamSpec>& specs, std::string_view name, std::string_view owner = {});

// Every parameter of `specs`: the given value checked, or the default. Throws InvalidArgument for
// an unknown name, a required parameter not given, or a value check_param refuses.
ParamValues resolve_params(const std::vector<ParamSpec>& specs, const ParamValues& given, std::string_view owner = {});
// Every parameter of `specs` at its default (throws InvalidArgument naming a required one).
ParamValues default_values(const std::vector<ParamSpec>& specs);

} // namespace geotandem
