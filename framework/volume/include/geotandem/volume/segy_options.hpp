#pragma once
// Where a SEG-Y file keeps what geotandem reads from its trace headers: the line numbers (inline,
// crossline) and the CDP coordinates (x, y), each at a 1-based byte of the 240-byte standard trace
// header with a declared type, and the coordinate scalar. The defaults are SEG-Y rev 1's; files
// delivered in practice put line numbers at 9/21, 5/21, 17/13 or 221/225, sometimes as floats.

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace geotandem::volume {

// A trace header field's encoding, in the file's byte order. The type fixes the width: int16 takes
// 2 bytes, the others 4.
enum class HeaderType {
  int16, // two's complement 16-bit integer
  int32, // two's complement 32-bit integer (SEG-Y's usual)
  ieee,  // IEEE 754 single precision float
  ibm,   // IBM System/360 single precision float
};
// "int16", "int32", "ieee", "ibm"; parse_header_type also takes "float" for "ieee". Throws
// InvalidArgument naming the accepted names.
HeaderType parse_header_type(const std::string& text);
const char* to_string(HeaderType type);
int width_of(HeaderType type); // bytes: 2 or 4

// One field: its first byte (1-based, as the standard counts) and its type. The field must end
// within the standard header: byte + width - 1 <= 240.
struct HeaderField {
  int byte = 0;
  HeaderType type = HeaderType::int32;
  bool operator==(const HeaderField&) const = default;
};

struct SegyOptions {
  int inline_byte = 189;
  int crossline_byte = 193;
  HeaderType inline_type = HeaderType::int32;
  HeaderType crossline_type = HeaderType::int32;
  int x_byte = 181; // CDP X
  int y_byte = 185; // CDP Y
  HeaderType x_type = HeaderType::int32;
  HeaderType y_type = HeaderType::int32;
  // The coordinate scalar of every trace instead of the one each trace header holds at bytes 71-72:
  // positive multiplies, negative divides, 0 means 1 (as in the header). Unset: the header's.
  std::optional<int> coordinate_scalar;
  bool operator==(const SegyOptions&) const = default;

  HeaderField inline_field() const { return {inline_byte, inline_type}; }
  HeaderField crossline_field() const { return {crossline_byte, crossline_type}; }
  HeaderField x_field() const { return {x_byte, x_type}; }
  HeaderField y_field() const { return {y_byte, y_type}; }
  // Only the line numbers' positions and types differ from `other` (what the common-position
  // probe changes).
  SegyOptions with_lines(int inline_at, int crossline_at) const {
    SegyOptions o = *this;
    o.inline_byte = inline_at;
    o.crossline_byte = crossline_at;
    o.inline_type = o.crossline_type = HeaderType::int32;
    return o;
  }
};

// Throws InvalidArgument (naming `where`, for example a file) when a field lies outside the
// 240-byte header, when the inline and crossline fields overlap, or when x and y overlap.
void check_segy_options(const SegyOptions& options, const std::string& where = {});

// JSON: {"inline_byte": 189, "crossline_byte": 193} always, the other keys (inline_type,
// crossline_type, x_byte, y_byte, x_type, y_type, coordinate_scalar) only where they differ from
// the defaults, so that the records of runs made before they existed read the same.
nlohmann::json to_json(const SegyOptions& options);
// Missing keys keep their defaults; throws InvalidArgument for a wrong type name or value.
SegyOptions segy_options_from_json(const nlohmann::json& json);

} // namespace geotandem::volume
