// Checks on numeric options (command.hpp): what CLI11's own conversions let through; and the options
// that say how a cube file is read, shared by the commands that open one.

#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>

#include "command.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/core/params.hpp"

namespace geotandem::app {
namespace {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// The value, when the whole text is a number ("nan" is one); otherwise CLI11 says what is wrong.
std::optional<double> number_of(const std::string& text) {
  const std::string t = trimmed(text);
  char* end = nullptr;
  const double value = std::strtod(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size()) return std::nullopt;
  return value;
}

// A validator from a test that returns what is wrong with the text, or nothing.
CLI::Validator rule(const char* name, std::string (*wrong)(const std::string&)) {
  return CLI::Validator([wrong](std::string& text) { return wrong(text); }, "", name);
}

} // namespace

const CLI::Validator& not_negative() {
  static const CLI::Validator check = rule("not negative", [](const std::string& text) -> std::string {
    return trimmed(text).rfind('-', 0) == 0 ? "'" + text + "' is negative; give a whole number from 0 up" : "";
  });
  return check;
}

const CLI::Validator& not_nan() {
  static const CLI::Validator check = rule("not NaN", [](const std::string& text) -> std::string {
    const auto value = number_of(text);
    return value && std::isnan(*value) ? "'" + text + "' is not a number; give a real number" : "";
  });
  return check;
}

std::optional<float> no_data_option(const std::optional<double>& value) {
  if (!value) return std::nullopt;
  const double largest = std::numeric_limits<float>::max();
  if (!(std::abs(*value) <= largest))
    throw InvalidArgument("--no-data is " + number_text(*value) + ", not a float sample's value", {},
                          "give the value the file's missing samples hold, such as -999.25");
  return static_cast<float>(*value);
}

const CLI::Validator& positive() {
  static const CLI::Validator check = rule("positive", [](const std::string& text) -> std::string {
    const auto value = number_of(text);
    if (value && std::isnan(*value)) return "'" + text + "' is not a number; give a number above 0";
    if (value && !(*value > 0.0)) return "'" + text + "' is not above 0; give a number above 0";
    return "";
  });
  return check;
}

namespace {
using HeaderTypeRef = volume::HeaderType*;
} // namespace

void add_cube_reading_options(CLI::App& cmd, std::string& variable, volume::SegyOptions& segy) {
  cmd.add_option("--variable", variable,
                 "the array to read from a multidimensional file (netCDF, Zarr, HDF5) that holds several");
  cmd.add_option("--inline-byte", segy.inline_byte,
                 "SEG-Y: trace header byte (1-based) of the inline numbers (often 9 or 5 in older files)")
      ->capture_default_str();
  cmd.add_option("--crossline-byte", segy.crossline_byte,
                 "SEG-Y: trace header byte (1-based) of the crossline numbers (often 21 or 13)")
      ->capture_default_str();
  // The types fix the width: int16 is 2 bytes, the others 4; any byte whose field ends by 240.
  const auto type_option = [&cmd](const std::string& name, HeaderTypeRef type, const std::string& help) {
    cmd.add_option_function<std::string>(
           name, [type](const std::string& text) { *type = volume::parse_header_type(text); }, help)
        ->check(CLI::IsMember({"int16", "int32", "ieee", "float", "ibm"}))
        ->default_str("int32")
        ->type_name("int16|int32|ieee|ibm");
  };
  type_option("--inline-type", &segy.inline_type,
              "SEG-Y: type of the inline field: int16, int32, ieee (IEEE float) or ibm (IBM float)");
  type_option("--crossline-type", &segy.crossline_type, "SEG-Y: type of the crossline field (as --inline-type)");
  cmd.add_option("--x-byte", segy.x_byte, "SEG-Y: trace header byte of the CDP X coordinates")->capture_default_str();
  cmd.add_option("--y-byte", segy.y_byte, "SEG-Y: trace header byte of the CDP Y coordinates")->capture_default_str();
  type_option("--x-type", &segy.x_type, "SEG-Y: type of the CDP X field (as --inline-type)");
  type_option("--y-type", &segy.y_type, "SEG-Y: type of the CDP Y field (as --inline-type)");
  cmd.add_option("--coordinate-scalar", segy.coordinate_scalar,
                 "SEG-Y: the coordinate scalar of every trace instead of bytes 71-72 of each header (negative "
                 "divides, 0 means 1)")
      ->type_name("INT");
}

} // namespace geotandem::app
