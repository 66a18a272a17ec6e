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
  return j;
}

const char* to_string(SampleUnit unit) {
  return unit == SampleUnit::milliseconds ? "ms" : "m";
}

SampleUnit parse_sample_unit(const std::string& text) {
  if (text == "ms") return SampleUnit::milliseconds;
  if (text == "m") return SampleUnit::metres;
  throw InvalidArgument("unknown sample unit '" + text + "'", {}, "use 'ms' for time or 'm' for depth");
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
