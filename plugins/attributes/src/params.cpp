#include "geotandem/attributes/params.hpp"

#include <charconv>
#include <cmath>

#include "geotandem/core/error.hpp"

namespace geotandem::attributes {
namespace {

// Shortest text that reads back to the same double ("2", "0.5", "1e+30").
std::string number_text(double value) {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string where(const AttributeSpec& spec, std::string_view name) {
  return "attribute '" + spec.name + "': parameter '" + std::string(name) + "'";
}

[[noreturn]] void reject(const AttributeSpec& spec, const ParamSpec& param, const std::string& value_text) {
  throw InvalidArgument(where(spec, param.name) + " is " + value_text + "; it must be " + param.valid_values(), {},
                        param.name + ": " + param.help);
}

std::string known_names(const AttributeSpec& spec) {
  std::string names;
  for (const ParamSpec& p : spec.params)
    names += (names.empty() ? "" : ", ") + p.name;
  return names.empty() ? "it takes no parameters" : "known parameters: " + names;
}

} // namespace

const char* to_string(ParamType type) {
  switch (type) {
  case ParamType::integer: return "integer";
  case ParamType::real: return "real";
  case ParamType::choice: return "choice";
  }
  return "?";
}

std::string to_string(const ParamValue& value) {
  if (const auto* i = std::get_if<std::int64_t>(&value)) return std::to_string(*i);
  if (const auto* d = std::get_if<double>(&value)) return number_text(*d);
  return std::get<std::string>(value);
}

std::string to_string(const ParamValues& values) {
  std::string text;
  for (const auto& [name, value] : values)
    text += (text.empty() ? "" : ", ") + name + "=" + to_string(value);
  return text;
}

bool ParamRange::contains(double value) const {
  if (std::isnan(value)) return false;
  bool above = min_open ? value > min : value >= min;
  bool below = max_open ? value < max : value <= max;
  return above && below;
}

std::string ParamRange::to_string() const {
  return std::string(min_open || std::isinf(min) ? "(" : "[") + number_text(min) + ", " + number_text(max) +
         (max_open || std::isinf(max) ? ")" : "]");
}

std::string ParamSpec::valid_values() const {
  switch (type) {
  case ParamType::integer: return std::string(odd ? "an odd integer" : "an integer") + " in " + range.to_string();
  case ParamType::real: return "a real in " + range.to_string();
  case ParamType::choice: {
    std::string words;
    for (const std::string& c : choices)
      words += (words.empty() ? "" : ", ") + c;
    return "one of " + words;
  }
  }
  return "?";
}

const ParamSpec& AttributeSpec::param(std::string_view wanted) const {
  for (const ParamSpec& p : params)
    if (p.name == wanted) return p;
  throw InvalidArgument("attribute '" + name + "' has no parameter '" + std::string(wanted) + "'", {},
                        known_names(*this));
}

void check_integer(const AttributeSpec& spec, std::string_view name, std::int64_t value) {
  const ParamSpec& p = spec.param(name);
  if (!p.range.contains(static_cast<double>(value)) || (p.odd && value % 2 == 0))
    reject(spec, p, std::to_string(value));
}

void check_real(const AttributeSpec& spec, std::string_view name, double value) {
  const ParamSpec& p = spec.param(name);
  if (!std::isfinite(value) || !p.range.contains(value)) reject(spec, p, number_text(value));
}

void check_choice(const AttributeSpec& spec, std::string_view name, const std::string& value) {
  const ParamSpec& p = spec.param(name);
  for (const std::string& c : p.choices)
    if (c == value) return;
  reject(spec, p, "'" + value + "'");
}

ParamValues resolve(const AttributeSpec& spec, const ParamValues& given) {
  for (const auto& [name, value] : given)
    spec.param(name); // unknown names throw
  ParamValues out;
  for (const ParamSpec& p : spec.params) {
    auto found = given.find(p.name);
    ParamValue value = found == given.end() ? p.default_value : found->second;
    switch (p.type) {
    case ParamType::integer:
      if (!std::holds_alternative<std::int64_t>(value))
        throw InvalidArgument(where(spec, p.name) + " is '" + to_string(value) + "'; it must be " + p.valid_values(),
                              {}, p.name + ": " + p.help);
      check_integer(spec, p.name, std::get<std::int64_t>(value));
      break;
    case ParamType::real:
      if (const auto* i = std::get_if<std::int64_t>(&value)) value = static_cast<double>(*i);
      if (!std::holds_alternative<double>(value))
        throw InvalidArgument(where(spec, p.name) + " is '" + to_string(value) + "'; it must be " + p.valid_values(),
                              {}, p.name + ": " + p.help);
      check_real(spec, p.name, std::get<double>(value));
      break;
    case ParamType::choice:
      if (!std::holds_alternative<std::string>(value))
        throw InvalidArgument(where(spec, p.name) + " is " + to_string(value) + "; it must be " + p.valid_values(), {},
                              p.name + ": " + p.help);
      check_choice(spec, p.name, std::get<std::string>(value));
      break;
    }
    out.emplace(p.name, std::move(value));
  }
  return out;
}

namespace {
template <class T> const T& get_typed(const ParamValues& values, std::string_view name, const char* type) {
  auto found = values.find(name);
  if (found == values.end())
    throw InvalidArgument("parameter '" + std::string(name) + "' is missing", {},
                          "resolve the parameters against the attribute's spec first");
  if (const T* v = std::get_if<T>(&found->second)) return *v;
  throw InvalidArgument("parameter '" + std::string(name) + "' is '" + to_string(found->second) + "', not " + type);
}
} // namespace

std::int64_t get_integer(const ParamValues& values, std::string_view name) {
  return get_typed<std::int64_t>(values, name, "an integer");
}
double get_real(const ParamValues& values, std::string_view name) {
  return get_typed<double>(values, name, "a real");
}
const std::string& get_choice(const ParamValues& values, std::string_view name) {
  return get_typed<std::string>(values, name, "a word");
}

} // namespace geotandem::attributes
