#include "geotandem/volume/geometry.hpp"

#include <cmath>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/geometry_json.hpp"

namespace geotandem::volume {

nlohmann::ordered_json geometry_fields_json(const Geometry& g) {
  const SurveyAffine& a = g.affine;
  nlohmann::ordered_json j;
  j["inline0"] = g.inline0;
  j["inline_step"] = g.inline_step;
  j["crossline0"] = g.crossline0;
  j["crossline_step"] = g.crossline_step;
  j["z0"] = g.z0;
  j["dz"] = g.dz;
  j["z_unit"] = to_string(g.z_unit);
  j["affine"] = {{"x0", a.x0}, {"xi", a.xi}, {"xj", a.xj}, {"y0", a.y0}, {"yi", a.yi}, {"yj", a.yj}};
  // Only when there is one: files and stores written before CRSs existed read the same.
  if (!g.crs.empty()) j["crs"] = crs_json(g.crs);
  return j;
}

nlohmann::ordered_json crs_json(const Crs& crs) {
  nlohmann::ordered_json j;
  j["name"] = crs.name;
  j["code"] = crs.code;
  j["unit"] = crs.unit;
  j["unit_name"] = crs.unit_name;
  j["metres_per_unit"] = crs.metres_per_unit;
  j["wkt"] = crs.wkt;
  return j;
}

Crs crs_from_json(const nlohmann::json& j) {
  if (!j.is_object()) throw InvalidArgument("the crs must be a JSON object (name, code, unit, unit_name, ...)");
  Crs crs;
  auto text = [&](const char* key, std::string& out) {
    if (!j.contains(key)) return;
    if (!j[key].is_string()) throw InvalidArgument(std::string("crs.") + key + " must be a string");
    out = j[key].get<std::string>();
  };
  text("name", crs.name);
  text("code", crs.code);
  text("unit", crs.unit);
  text("unit_name", crs.unit_name);
  text("wkt", crs.wkt);
  if (j.contains("metres_per_unit")) {
    if (!j["metres_per_unit"].is_number() || !(j["metres_per_unit"].get<double>() > 0.0))
      throw InvalidArgument("crs.metres_per_unit must be a positive number");
    crs.metres_per_unit = j["metres_per_unit"].get<double>();
  }
  if (crs.wkt.empty()) throw InvalidArgument("crs.wkt is missing or empty", {}, "leave the crs out when there is none");
  return crs;
}

std::string Crs::label() const {
  if (empty()) return kNoCrs;
  std::string text = name.empty() ? std::string("unnamed CRS") : name;
  if (!code.empty()) text += " (" + code + ")";
  return text;
}

std::string volume_unit(const Geometry& g) {
  const std::string xy = g.crs.empty() ? std::string("m") : g.crs.unit;
  const std::string z = to_string(g.z_unit);
  if (z == xy) return xy + "^3";
  return xy + "^2*" + z;
}

bool Geometry::same_grid(const Geometry& other) const {
  Geometry a = *this, b = other;
  a.crs = b.crs = Crs{};
  return a == b;
}

const char* to_string(SampleUnit unit) {
  switch (unit) {
  case SampleUnit::milliseconds: return "ms";
  case SampleUnit::metres: return "m";
  case SampleUnit::feet: return "ft";
  }
  return "ms";
}

SampleUnit parse_sample_unit(const std::string& text) {
  if (text == "ms") return SampleUnit::milliseconds;
  if (text == "m") return SampleUnit::metres;
  if (text == "ft") return SampleUnit::feet;
  throw InvalidArgument("unknown sample unit '" + text + "'", {},
                        "use 'ms' for time, 'm' for depth in metres or 'ft' for depth in feet");
}

double SurveyAffine::step_i() const {
  return std::hypot(xi, yi);
}
double SurveyAffine::step_j() const {
  return std::hypot(xj, yj);
}

std::array<double, 3> Geometry::world(double i, double j, double k) const {
  auto xy = affine.apply(i, j);
  return {xy[0], xy[1], z0 + dz * k};
}

void Geometry::validate() const {
  static constexpr const char* names[] = {"inline", "crossline", "sample"};
  for (int a = 0; a < 3; ++a)
    if (shape[a] <= 0)
      throw InvalidArgument(std::string("the ") + names[a] + " axis has " + std::to_string(shape[a]) +
                            " samples; every axis needs at least one");
  if (!(dz > 0.0) || !std::isfinite(dz))
    throw InvalidArgument("the sample interval dz is " + std::to_string(dz) + "; it must be positive");
  double det = affine.xi * affine.yj - affine.xj * affine.yi;
  if (!(std::abs(det) > 0.0) || !std::isfinite(det))
    throw InvalidArgument("the survey affine is degenerate (inline and crossline directions are parallel)", {},
                          "check the CDP_X/CDP_Y coordinates of the corner traces");
}

} // namespace geotandem::volume
