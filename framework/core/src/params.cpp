#include "geotandem/core/params.hpp"
#include "geotandem/core/param_fields.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>

#include "geotandem/core/error.hpp"
#include "geotandem/core/suggest.hpp"

namespace geotandem {
namespace {

std::string list_of(const std::vector<std::string>& words) {
  std::string text;
  for (const auto& w : words)
    text += (text.empty() ? "" : ", ") + w;
  return text;
}

// "attribute 'chaos': parameter 'sigma_g'" or "parameter 'sigma_g'".
std::string named(const ParamSpec& spec, std::string_view owner) {
  return (owner.empty() ? std::string() : std::string(owner) + ": ") + "parameter '" + spec.name + "'";
}

std::string help_hint(const ParamSpec& spec) {
  return spec.help.empty() ? std::string() : spec.name + ": " + spec.help;
}

// The interval in words, for hints: "between 0.1 and 10", "above 0 and at most 20", "at least 8".
std::string range_words(const ParamSpec& spec) {
  const auto& lo = spec.min_value;
  const auto& hi = spec.max_value;
  if (lo && hi && !spec.min_open && !spec.max_open) return "between " + number_text(*lo) + " and " + number_text(*hi);
  std::string text;
  if (lo) text += (spec.min_open ? "above " : "at least ") + number_text(*lo);
  if (lo && hi) text += " and ";
  if (hi) text += (spec.max_open ? "below " : "at most ") + number_text(*hi);
  return text;
}

[[noreturn]] void wrong_type(const ParamSpec& spec, const std::string& text, std::string_view owner) {
  throw InvalidArgument(named(spec, owner) + " is '" + text + "', not " + spec.valid_values(), {}, help_hint(spec));
}

void check_number(const ParamSpec& spec, double value, const std::string& text, std::string_view owner) {
  if (!spec.in_range(value))
    throw InvalidArgument(named(spec, owner) + " is " + text + ", out of range: it must be " + spec.valid_values(), {},
                          "use a value " + range_words(spec));
  // Refused from the midpoint between the largest float and 2^128 on, where a conversion to float
  // rounds to infinity (a conversion that is undefined behaviour in C++): the bound printed below
  // rounds to the largest float, so it is accepted.
  constexpr double rounds_to_infinity = 0x1.ffffffp127;
  if (spec.single_precision && !(std::abs(value) < rounds_to_infinity))
    throw InvalidArgument(
        named(spec, owner) + " is " + text + ", beyond the range of a 32-bit float: it must lie between -" +
            number_text(std::numeric_limits<float>::max()) + " and " + number_text(std::numeric_limits<float>::max()),
        {},
        "the value is used as a 32-bit float, as the cube's samples are: give one within the samples' range "
        "(geotandem info CUBE shows it)");
  // Likewise at the other end: a value that is not 0 but rounds to 0 as a float (below half the
  // smallest subnormal float, 2^-150) would divide by zero or compare as 0.
  constexpr double rounds_to_zero = 0x1p-150;
  if (spec.single_precision && value != 0.0 && std::abs(value) <= rounds_to_zero)
    throw InvalidArgument(named(spec, owner) + " is " + text +
                              ", closer to 0 than a 32-bit float can hold: the smallest is " +
                              number_text(std::numeric_limits<float>::denorm_min()),
                          {}, "the value is used as a 32-bit float, as the cube's samples are");
}

void check_odd(const ParamSpec& spec, std::int64_t n, std::string_view owner) {
  if (!spec.odd || n % 2 != 0) return;
  std::string neighbours;
  for (std::int64_t m : {n - 1, n + 1})
    if (spec.in_range(static_cast<double>(m))) neighbours += (neighbours.empty() ? "" : " or ") + std::to_string(m);
  throw InvalidArgument(named(spec, owner) + " is " + std::to_string(n) + ", not odd: it must be " +
                            spec.valid_values(),
                        {}, "a centred window has an odd length: use " + neighbours);
}

void check_choice(const ParamSpec& spec, const std::string& word, std::string_view owner) {
  for (const auto& c : spec.choices)
    if (c == word) return;
  throw InvalidArgument(named(spec, owner) + " is '" + word + "', not a known choice: it must be " +
                            spec.valid_values(),
                        {}, suggestion_hint(word, spec.choices));
}

// A size in MiB ("2048M", "4G", "512", "1.5G") or a duration in seconds ("1:30:00", "90:00" as
// hh:mm, "90" minutes); nullopt when `text` is neither.
std::optional<std::int64_t> read_form(ParamSpec::Form form, const std::string& text) {
  if (form == ParamSpec::Form::size_mib) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || errno || !std::isfinite(v) || v < 0) return std::nullopt;
    const std::string unit = end;
    const double scale = unit.empty() || unit == "M" || unit == "MB" || unit == "MiB" ? 1.0
                         : unit == "G" || unit == "GB" || unit == "GiB"               ? 1024.0
                         : unit == "T" || unit == "TB" || unit == "TiB"               ? 1024.0 * 1024.0
                                                                                      : -1.0;
    if (scale < 0 || v * scale > 1e15) return std::nullopt;
    return static_cast<std::int64_t>(v * scale);
  }
  // [[hh:]mm:]ss: every part digits, minutes and seconds below 60 after the first part
  std::vector<std::int64_t> parts;
  std::size_t at = 0;
  while (true) {
    std::size_t end = text.find(':', at);
    const std::string part = text.substr(at, end == std::string::npos ? std::string::npos : end - at);
    if (part.empty() || part.size() > 9 || part.find_first_not_of("0123456789") != std::string::npos)
      return std::nullopt;
    parts.push_back(std::stoll(part));
    if (end == std::string::npos) break;
    at = end + 1;
  }
  if (parts.size() > 3) return std::nullopt;
  for (std::size_t i = 1; i < parts.size(); ++i)
    if (parts[i] >= 60) return std::nullopt;
  if (parts.size() == 1) return parts[0] * 60;                   // minutes
  if (parts.size() == 2) return parts[0] * 3600 + parts[1] * 60; // hh:mm
  return parts[0] * 3600 + parts[1] * 60 + parts[2];             // hh:mm:ss
}

// A text value in a form: its integer set, or the error.
void check_form(const ParamSpec& spec, ParamValue& v, std::string_view owner) {
  if (spec.form == ParamSpec::Form::plain) return;
  const std::optional<std::int64_t> n = read_form(spec.form, v.text);
  if (!n) wrong_type(spec, v.text, owner);
  v.integer = *n;
  v.real = static_cast<double>(*n);
  if (!spec.in_range(v.real))
    throw InvalidArgument(
        named(spec, owner) + " is " + v.text + ", out of range: it must be " + spec.valid_values(), {},
        "use a value " + range_words(spec) + (spec.form == ParamSpec::Form::size_mib ? " MiB" : " s"));
}

} // namespace

ParamSpec ParamSpec::entry() const {
  ParamSpec e = *this;
  e.type = item_type;
  e.list = false;
  e.list_length = 0;
  e.name = name; // messages name the list; the caller adds the position
  return e;
}

const char* to_string(ParamType type) {
  switch (type) {
  case ParamType::integer: return "integer";
  case ParamType::real: return "real";
  case ParamType::boolean: return "boolean";
  case ParamType::text: return "text";
  case ParamType::choice: return "choice";
  }
  return "?";
}

std::string number_text(double value) {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string number_text(float value) {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[32];
  auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

bool ParamSpec::in_range(double value) const {
  if (std::isnan(value)) return false;
  bool above = !min_value || (min_open ? value > *min_value : value >= *min_value);
  bool below = !max_value || (max_open ? value < *max_value : value <= *max_value);
  return above && below;
}

std::string ParamSpec::range_text() const {
  const bool closed_lo = min_value && !min_open && std::isfinite(*min_value);
  const bool closed_hi = max_value && !max_open && std::isfinite(*max_value);
  // An integer's bounds in digits ("100000", not "1e+05").
  const auto bound = [&](double v) {
    const bool whole = (type == ParamType::integer || form != Form::plain || item_type == ParamType::integer) &&
                       std::abs(v) < 9e15 && std::floor(v) == v;
    return whole ? std::to_string(static_cast<std::int64_t>(v)) : number_text(v);
  };
  return std::string(closed_lo ? "[" : "(") + (min_value ? bound(*min_value) : "-inf") + ", " +
         (max_value ? bound(*max_value) : "inf") + (closed_hi ? "]" : ")");
}

std::string ParamSpec::valid_values() const {
  const bool bounded = min_value || max_value;
  switch (type) {
  case ParamType::integer:
    return std::string(odd ? "an odd integer" : "an integer") + (bounded ? " in " + range_text() : "");
  case ParamType::real: return bounded ? "a real in " + range_text() : "a real";
  case ParamType::boolean: return "true or false";
  case ParamType::text: break;
  case ParamType::choice: return "one of " + list_of(choices);
  }
  if (list) {
    ParamSpec e = entry();
    const std::string count = list_length ? std::to_string(list_length) + " " : std::string();
    if (table_items) return "a list of " + count + "tables";
    if (e.type == ParamType::text && e.form == Form::plain) return "a list of " + count + "words";
    return "a list of " + count + "entries, each " + e.valid_values();
  }
  switch (form) {
  // The lower bound (1 MiB, 1 s) is the out-of-range message's hint ("use a value at least 1").
  case Form::size_mib: return "a size such as 2048M or 4G (MiB unless G or T follows)";
  case Form::duration_s: return "a duration hh:mm:ss, hh:mm or minutes";
  case Form::plain: break;
  }
  return "text";
}

ParamValue ParamValue::integer_value(std::int64_t value) {
  ParamValue v;
  v.type = ParamType::integer;
  v.integer = value;
  v.real = static_cast<double>(value);
  v.text = std::to_string(value);
  return v;
}

ParamValue::ParamValue(double value) : type(ParamType::real), real(value), text(number_text(value)) {}

ParamValue::ParamValue(bool value) : type(ParamType::boolean), boolean(value), text(value ? "true" : "false") {}

ParamValue::ParamValue(std::string word) : type(ParamType::text), text(std::move(word)) {}

bool operator==(const ParamValue& a, const ParamValue& b) {
  auto family = [](ParamType t) { return t == ParamType::choice ? ParamType::text : t; }; // a word either way
  if (family(a.type) != family(b.type)) return false;
  switch (a.type) {
  case ParamType::integer: return a.integer == b.integer;
  case ParamType::real: return a.real == b.real;
  case ParamType::boolean: return a.boolean == b.boolean;
  case ParamType::text:
  case ParamType::choice: return a.text == b.text;
  }
  return false;
}

std::string to_string(const ParamValues& values) {
  std::string text;
  for (const auto& [name, value] : values)
    text += (text.empty() ? "" : ", ") + name + "=" + value.text;
  return text;
}

ParamValue parse_param(const ParamSpec& spec, const std::string& text, std::string_view owner) {
  ParamValue v;
  v.type = spec.type;
  v.text = text;
  switch (spec.type) {
  case ParamType::integer: {
    char* end = nullptr;
    errno = 0;
    long long n = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno) wrong_type(spec, text, owner);
    v.integer = n;
    v.real = static_cast<double>(n);
    check_number(spec, v.real, text, owner);
    check_odd(spec, n, owner);
    break;
  }
  case ParamType::real: {
    char* end = nullptr;
    errno = 0;
    double x = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || errno || !std::isfinite(x)) wrong_type(spec, text, owner);
    v.real = x;
    check_number(spec, x, text, owner);
    break;
  }
  case ParamType::boolean:
    if (text == "true" || text == "yes" || text == "on")
      v.boolean = true;
    else if (text == "false" || text == "no" || text == "off")
      v.boolean = false;
    else
      wrong_type(spec, text, owner);
    break;
  case ParamType::text: check_form(spec, v, owner); break;
  case ParamType::choice: check_choice(spec, text, owner); break;
  }
  return v;
}

ParamValue check_param(const ParamSpec& spec, const ParamValue& value, std::string_view owner) {
  ParamValue v = value;
  switch (spec.type) {
  case ParamType::integer:
    if (value.type != ParamType::integer) wrong_type(spec, value.text, owner);
    check_number(spec, v.real, v.text, owner);
    check_odd(spec, v.integer, owner);
    break;
  case ParamType::real:
    if (value.type == ParamType::integer) v = ParamValue(static_cast<double>(value.integer));
    if (v.type != ParamType::real || !std::isfinite(v.real)) wrong_type(spec, v.text, owner);
    check_number(spec, v.real, v.text, owner);
    break;
  case ParamType::boolean:
    if (value.type != ParamType::boolean) wrong_type(spec, value.text, owner);
    break;
  case ParamType::text:
  case ParamType::choice:
    if (value.type != ParamType::text && value.type != ParamType::choice) wrong_type(spec, value.text, owner);
    if (spec.type == ParamType::choice) check_choice(spec, v.text, owner);
    v.type = spec.type;
    if (spec.type == ParamType::text) check_form(spec, v, owner);
    break;
  }
  return v;
}

const ParamSpec& find_param(const std::vector<ParamSpec>& specs, std::string_view name, std::string_view owner) {
  std::vector<std::string> names;
  for (const auto& p : specs) {
    if (p.name == name) return p;
    names.push_back(p.name);
  }
  const std::string close = nearest(std::string(name), names);
  throw InvalidArgument(
      (owner.empty() ? std::string("unknown parameter '") : std::string(owner) + " has no parameter '") +
          std::string(name) + "'",
      {},
      names.empty()
          ? "it takes no parameters"
          : (close.empty() ? std::string() : "did you mean '" + close + "'? ") + "known parameters: " + list_of(names));
}

ParamValues resolve_params(const std::vector<ParamSpec>& specs, const ParamValues& given, std::string_view owner) {
  for (const auto& entry : given)
    find_param(specs, entry.first, owner); // unknown names throw
  ParamValues out;
  for (const auto& spec : specs) {
    auto found = given.find(spec.name);
    if (found != given.end())
      out.emplace(spec.name, check_param(spec, found->second, owner));
    else if (spec.default_value)
      out.emplace(spec.name, parse_param(spec, *spec.default_value, owner));
    else
      throw InvalidArgument(named(spec, owner) + " is required", {}, help_hint(spec));
  }
  return out;
}

ParamValues default_values(const std::vector<ParamSpec>& specs) {
  ParamValues values;
  for (const auto& spec : specs) {
    if (!spec.default_value) throw InvalidArgument("parameter '" + spec.name + "' has no default", {}, help_hint(spec));
    values[spec.name] = parse_param(spec, *spec.default_value);
  }
  return values;
}

ParamSpec param_spec(std::string name, ParamType type, std::optional<std::string> default_value, std::string help,
                     std::optional<double> min_value, std::optional<double> max_value,
                     std::vector<std::string> choices) {
  ParamSpec s;
  s.name = std::move(name);
  s.type = type;
  s.default_value = std::move(default_value);
  s.help = std::move(help);
  s.min_value = min_value;
  s.max_value = max_value;
  s.choices = std::move(choices);
  return s;
}

} // namespace geotandem
