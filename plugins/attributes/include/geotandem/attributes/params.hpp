#pragma once
// Parameter descriptions as data. Every attribute publishes an AttributeSpec (name, inputs, and per
// parameter: name, type, default, valid values, unit, help). The same table validates typed
// options in C++, checks the parameters a recipe gives, lists plugins and writes the docs, so the
// plugin layer can wrap an attribute without knowing its options struct.

#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace geotandem::attributes {

enum class ParamType { integer, real, choice };
// "integer", "real" or "choice".
const char* to_string(ParamType type);

// A parameter value as a recipe gives it: an integer, a real or a word.
using ParamValue = std::variant<std::int64_t, double, std::string>;
// The value as a recipe would write it ("9", "2.5", "planarity").
std::string to_string(const ParamValue& value);

// A numeric interval; each end is closed unless marked open. Infinite ends mean "no bound".
struct ParamRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;

  bool contains(double value) const;
  // "[1, 1001]", "(0, 20]", "(0, inf)".
  std::string to_string() const;
};

struct ParamSpec {
  std::string name;
  ParamType type = ParamType::real;
  ParamValue default_value;
  ParamRange range;                 // integer and real parameters
  bool odd = false;                 // integer parameters that must be odd (window lengths)
  std::vector<std::string> choices; // choice parameters: the accepted words
  std::string unit;                 // "samples", "traces", "percent", or empty
  std::string help;

  // What the parameter accepts, for messages and listings: "odd integer in [1, 1001]",
  // "real in (0, 20]", "one of planarity, marfurt".
  std::string valid_values() const;
};

struct AttributeSpec {
  std::string name;
  std::string summary;
  int inputs = 1; // number of input volumes
  std::vector<ParamSpec> params;

  // The parameter called `name`; throws InvalidArgument listing the known ones otherwise.
  const ParamSpec& param(std::string_view name) const;
};

// Parameters by name, as given by a recipe (possibly partial) or as resolved (complete).
using ParamValues = std::map<std::string, ParamValue, std::less<>>;

// "name=value, name=value" in the map's order, for messages and source() descriptions.
std::string to_string(const ParamValues& values);

// Checks `given` against `spec` and returns every parameter, defaults filled in. An integer is
// accepted for a real parameter. Throws InvalidArgument naming the attribute and the parameter for
// an unknown name (listing the known ones), a wrong type, or a value outside the valid values.
ParamValues resolve(const AttributeSpec& spec, const ParamValues& given);

// Range checks used by the options structs' validate(); each throws InvalidArgument whose message
// names the attribute, the parameter, the value and the valid values.
void check_integer(const AttributeSpec& spec, std::string_view name, std::int64_t value);
void check_real(const AttributeSpec& spec, std::string_view name, double value);
void check_choice(const AttributeSpec& spec, std::string_view name, const std::string& value);

// Typed access to a resolved set (see resolve); throws InvalidArgument if the parameter is missing
// or of another type.
std::int64_t get_integer(const ParamValues& values, std::string_view name);
double get_real(const ParamValues& values, std::string_view name);
const std::string& get_choice(const ParamValues& values, std::string_view name);

} // namespace geotandem::attributes
