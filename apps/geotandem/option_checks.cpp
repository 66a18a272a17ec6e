// Checks on numeric options (command.hpp): what CLI11's own conversions let through.

#include <cmath>
#include <cstdlib>
#include <string>

#include "command.hpp"

namespace geotandem::app {
namespace {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// The value as a double, or NaN when it is not a number at all (CLI11 then says so itself).
double real_of(const std::string& text) {
  const std::string t = trimmed(text);
  char* end = nullptr;
  const double value = std::strtod(t.c_str(), &end);
  return !t.empty() && end == t.c_str() + t.size() ? value : std::nan("");
}

bool is_nan_text(const std::string& text) {
  const std::string t = trimmed(text);
  char* end = nullptr;
  const double value = std::strtod(t.c_str(), &end);
  return !t.empty() && end == t.c_str() + t.size() && std::isnan(value);
}

} // namespace

const CLI::Validator& not_negative() {
  static const CLI::Validator check(
      [](std::string& text) -> std::string {
        if (trimmed(text).rfind('-', 0) == 0) return "'" + text + "' is negative; give a whole number from 0 up";
        return {};
      },
      "", "not negative");
  return check;
}

const CLI::Validator& not_nan() {
  static const CLI::Validator check(
      [](std::string& text) -> std::string {
        if (is_nan_text(text)) return "'" + text + "' is not a number; give a real number";
        return {};
      },
      "", "not NaN");
  return check;
}

const CLI::Validator& positive() {
  static const CLI::Validator check(
      [](std::string& text) -> std::string {
        const double value = real_of(text);
        if (is_nan_text(text)) return "'" + text + "' is not a number; give a number above 0";
        if (!std::isnan(value) && !(value > 0.0)) return "'" + text + "' is not above 0; give a number above 0";
        return {};
      },
      "", "positive");
  return check;
}

} // namespace geotandem::app
