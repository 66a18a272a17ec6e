// SegyOptions: names of header types, checks and the JSON codec.

#include "geotandem/volume/segy_options.hpp"

#include "geotandem/core/error.hpp"

namespace geotandem::volume {

HeaderType parse_header_type(const std::string& text) {
  if (text == "int16") return HeaderType::int16;
  if (text == "int32") return HeaderType::int32;
  if (text == "ieee" || text == "float") return HeaderType::ieee;
  if (text == "ibm") return HeaderType::ibm;
  throw InvalidArgument("unknown SEG-Y header type '" + text + "'", {},
                        "give int16, int32, ieee (IEEE float, also 'float') or ibm (IBM float)");
}

const char* to_string(HeaderType type) {
  switch (type) {
  case HeaderType::int16: return "int16";
  case HeaderType::int32: return "int32";
  case HeaderType::ieee: return "ieee";
  case HeaderType::ibm: return "ibm";
  }
  return "int32";
}

int width_of(HeaderType type) {
  return type == HeaderType::int16 ? 2 : 4;
}

namespace {

constexpr int kHeaderBytes = 240;

void check_field(const HeaderField& f, const char* what, const std::string& where) {
  const int last = f.byte + width_of(f.type) - 1;
  if (f.byte < 1 || last > kHeaderBytes)
    throw InvalidArgument(std::string("the ") + what + " field at byte " + std::to_string(f.byte) + " (" +
                              to_string(f.type) + ", " + std::to_string(width_of(f.type)) +
                              " bytes) lies outside the 240-byte trace header",
                          {where},
                          "give a byte from 1 to " + std::to_string(kHeaderBytes - width_of(f.type) + 1) +
                              " for a field of " + std::to_string(width_of(f.type)) + " bytes");
}

bool overlap(const HeaderField& a, const HeaderField& b) {
  return a.byte < b.byte + width_of(b.type) && b.byte < a.byte + width_of(a.type);
}

} // namespace

void check_segy_options(const SegyOptions& o, const std::string& where) {
  check_field(o.inline_field(), "inline", where);
  check_field(o.crossline_field(), "crossline", where);
  check_field(o.x_field(), "CDP X", where);
  check_field(o.y_field(), "CDP Y", where);
  if (o.inline_byte == o.crossline_byte)
    throw InvalidArgument("the inline and crossline byte positions are both " + std::to_string(o.inline_byte), {where},
                          "give two different positions, for example 189 and 193");
  if (overlap(o.inline_field(), o.crossline_field()))
    throw InvalidArgument("the inline field (bytes " + std::to_string(o.inline_byte) + "-" +
                              std::to_string(o.inline_byte + width_of(o.inline_type) - 1) +
                              ") and the crossline field (bytes " + std::to_string(o.crossline_byte) + "-" +
                              std::to_string(o.crossline_byte + width_of(o.crossline_type) - 1) + ") overlap",
                          {where}, "check the byte positions and types of the line numbers");
  if (overlap(o.x_field(), o.y_field()))
    throw InvalidArgument("the CDP X field (byte " + std::to_string(o.x_byte) + ") and the CDP Y field (byte " +
                              std::to_string(o.y_byte) + ") overlap",
                          {where}, "check the byte positions and types of the coordinates");
}

nlohmann::json to_json(const SegyOptions& o) {
  nlohmann::json j{{"inline_byte", o.inline_byte}, {"crossline_byte", o.crossline_byte}};
  const SegyOptions d;
  if (o.inline_type != d.inline_type) j["inline_type"] = to_string(o.inline_type);
  if (o.crossline_type != d.crossline_type) j["crossline_type"] = to_string(o.crossline_type);
  if (o.x_byte != d.x_byte) j["x_byte"] = o.x_byte;
  if (o.y_byte != d.y_byte) j["y_byte"] = o.y_byte;
  if (o.x_type != d.x_type) j["x_type"] = to_string(o.x_type);
  if (o.y_type != d.y_type) j["y_type"] = to_string(o.y_type);
  if (o.coordinate_scalar) j["coordinate_scalar"] = *o.coordinate_scalar;
  return j;
}

SegyOptions segy_options_from_json(const nlohmann::json& j) {
  SegyOptions o;
  try {
    o.inline_byte = j.value("inline_byte", o.inline_byte);
    o.crossline_byte = j.value("crossline_byte", o.crossline_byte);
    o.x_byte = j.value("x_byte", o.x_byte);
    o.y_byte = j.value("y_byte", o.y_byte);
    if (j.contains("inline_type")) o.inline_type = parse_header_type(j.at("inline_type").get<std::string>());
    if (j.contains("crossline_type")) o.crossline_type = parse_header_type(j.at("crossline_type").get<std::string>());
    if (j.contains("x_type")) o.x_type = parse_header_type(j.at("x_type").get<std::string>());
    if (j.contains("y_type")) o.y_type = parse_header_type(j.at("y_type").get<std::string>());
    if (j.contains("coordinate_scalar") && !j.at("coordinate_scalar").is_null())
      o.coordinate_scalar = j.at("coordinate_scalar").get<int>();
  } catch (const nlohmann::json::exception& e) {
    throw InvalidArgument(std::string("SEG-Y header options: ") + e.what());
  }
  return o;
}

} // namespace geotandem::volume
