// The raw cube's JSON sidecar: reading with checks that name the key and the file, and writing.
#include "raw_sidecar.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/geometry_json.hpp"

namespace fs = std::filesystem;

namespace geotandem::volume::detail {
namespace {

using json = nlohmann::json;

constexpr const char* kTag = "geotandem-raw";
constexpr int kVersion = 1;

// Checks one JSON object against the keys it must have, naming `where` (a dotted key path) and
// the sidecar file in every error.
class SidecarReader {
public:
  explicit SidecarReader(std::string file) : file_(std::move(file)) {}

  void expect_keys(const json& object, const std::string& where, std::initializer_list<const char*> keys,
                   std::initializer_list<const char*> optional = {}) const {
    if (!object.is_object()) fail("'" + where + "' must be a JSON object");
    std::string known;
    for (const char* key : keys)
      known += std::string(known.empty() ? "" : ", ") + key;
    for (const char* key : optional)
      known += std::string(", ") + key + " (optional)";
    for (const auto& item : object.items()) {
      bool found = false;
      for (const char* key : keys)
        found = found || item.key() == key;
      for (const char* key : optional)
        found = found || item.key() == key;
      if (!found) fail("unknown key '" + join(where, item.key()) + "'", "the keys here are: " + known);
    }
    for (const char* key : keys)
      if (!object.contains(key)) fail("missing key '" + join(where, key) + "'", "the keys here are: " + known);
  }

  double number(const json& object, const std::string& where, const char* key) const {
    const json& value = object.at(key);
    if (!value.is_number()) fail("key '" + join(where, key) + "' must be a number, found " + value.dump());
    return value.get<double>();
  }

  std::string text(const json& object, const std::string& where, const char* key) const {
    const json& value = object.at(key);
    if (!value.is_string()) fail("key '" + join(where, key) + "' must be a string, found " + value.dump());
    return value.get<std::string>();
  }

  void expect_text(const json& object, const char* key, const std::string& wanted) const {
    std::string found = text(object, "", key);
    if (found != wanted)
      fail("key '" + std::string(key) + "' is \"" + found + "\"; geotandem raw files have \"" + wanted + "\"");
  }

  [[noreturn]] void fail(const std::string& message, const std::string& hint = {}) const {
    throw FormatError("raw sidecar: " + message, {file_},
                      hint.empty() ? "see docs/formats-segy-raw.md for the sidecar's keys" : hint);
  }

private:
  static std::string join(const std::string& where, const std::string& key) {
    return where.empty() ? key : where + "." + key;
  }
  std::string file_;
};

// 1-based line and column of a byte offset, for parse errors.
ErrorContext position_of(const std::string& file, const std::string& text, std::size_t byte) {
  ErrorContext where{file};
  long line = 1, column = 1;
  for (std::size_t n = 0; n + 1 < byte && n < text.size(); ++n) {
    if (text[n] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  where.line = line;
  where.column = column;
  return where;
}

} // namespace

Geometry read_raw_sidecar(const std::string& sidecar) {
  // A FIFO or device would block or never end; a sidecar is a page of JSON.
  std::error_code ec;
  if (!fs::is_regular_file(sidecar, ec))
    throw IoError("the raw sidecar is not a regular file (a FIFO, a device or a directory)", {sidecar},
                  "write the sidecar as a JSON file");
  if (fs::file_size(sidecar, ec) > (1u << 20))
    throw FormatError("the raw sidecar is larger than 1 MiB; a sidecar is a page of JSON", {sidecar});
  std::ifstream in(sidecar, std::ios::binary);
  if (!in) throw IoError("cannot read the raw sidecar", {sidecar}, "check that it exists and is readable");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    throw FormatError(std::string("raw sidecar is not valid JSON: ") + e.what(), position_of(sidecar, text, e.byte),
                      "fix the JSON syntax; see docs/formats-segy-raw.md");
  } catch (const json::exception& e) {
    // Valid syntax the parser still cannot hold, such as a number beyond a double (found by fuzz_raw_sidecar).
    throw FormatError(std::string("raw sidecar cannot be read: ") + e.what(), {sidecar},
                      "write numbers a double can hold; see docs/formats-segy-raw.md");
  }

  SidecarReader r(sidecar);
  r.expect_keys(doc, "", {"format", "version", "dtype", "byte_order", "order", "axes", "shape", "geometry"});
  r.expect_text(doc, "format", kTag);
  const json& version = doc.at("version");
  if (!version.is_number_integer() || version.get<long long>() < 1)
    r.fail("key 'version' must be a positive integer, found " + version.dump());
  if (version.get<long long>() > kVersion)
    r.fail("sidecar version " + version.dump() + " is newer than this geotandem reads (" + std::to_string(kVersion) +
               ")",
           "update geotandem");
  r.expect_text(doc, "dtype", "float32");
  r.expect_text(doc, "byte_order", "little");
  r.expect_text(doc, "order", "C");
  if (doc.at("axes") != json::array({"inline", "crossline", "sample"}))
    r.fail("key 'axes' must be [\"inline\", \"crossline\", \"sample\"], found " + doc.at("axes").dump());

  Geometry g;
  const json& shape = doc.at("shape");
  if (!shape.is_array() || shape.size() != 3) r.fail("key 'shape' must be [inlines, crosslines, samples]");
  for (std::size_t a = 0; a < 3; ++a) {
    if (!shape[a].is_number_integer() || shape[a].get<long long>() < 1)
      r.fail("key 'shape' must hold three positive integers, found " + shape.dump());
    g.shape[a] = shape[a].get<std::int64_t>();
  }

  const json& geo = doc.at("geometry");
  r.expect_keys(geo, "geometry",
                {"inline0", "inline_step", "crossline0", "crossline_step", "z0", "dz", "z_unit", "affine"}, {"crs"});
  g.inline0 = r.number(geo, "geometry", "inline0");
  g.inline_step = r.number(geo, "geometry", "inline_step");
  g.crossline0 = r.number(geo, "geometry", "crossline0");
  g.crossline_step = r.number(geo, "geometry", "crossline_step");
  g.z0 = r.number(geo, "geometry", "z0");
  g.dz = r.number(geo, "geometry", "dz");
  const std::string unit = r.text(geo, "geometry", "z_unit");
  try {
    g.z_unit = parse_sample_unit(unit);
  } catch (const InvalidArgument&) {
    r.fail("key 'geometry.z_unit' is \"" + unit + "\"", "use \"ms\" (time), \"m\" or \"ft\" (depth)");
  }
  const json& affine = geo.at("affine");
  r.expect_keys(affine, "geometry.affine", {"x0", "xi", "xj", "y0", "yi", "yj"});
  g.affine.x0 = r.number(affine, "geometry.affine", "x0");
  g.affine.xi = r.number(affine, "geometry.affine", "xi");
  g.affine.xj = r.number(affine, "geometry.affine", "xj");
  g.affine.y0 = r.number(affine, "geometry.affine", "y0");
  g.affine.yi = r.number(affine, "geometry.affine", "yi");
  g.affine.yj = r.number(affine, "geometry.affine", "yj");
  if (geo.contains("crs")) {
    try {
      g.crs = crs_from_json(geo.at("crs"));
    } catch (const InvalidArgument& e) {
      r.fail("key 'geometry.crs': " + e.message(), e.hint());
    }
  }
  try {
    g.validate();
  } catch (const InvalidArgument& e) {
    r.fail("the geometry is invalid: " + e.message(), e.hint());
  }
  return g;
}

std::string raw_sidecar_text(const Geometry& g) {
  using ordered = nlohmann::ordered_json;
  ordered doc;
  doc["format"] = kTag;
  doc["version"] = kVersion;
  doc["dtype"] = "float32";
  doc["byte_order"] = "little";
  doc["order"] = "C";
  doc["axes"] = {"inline", "crossline", "sample"};
  doc["shape"] = {g.shape[0], g.shape[1], g.shape[2]};
  doc["geometry"] = geometry_fields_json(g);
  return doc.dump(2) + "\n";
}

} // namespace geotandem::volume::detail
