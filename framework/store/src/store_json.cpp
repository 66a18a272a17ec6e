// store.json helpers: the cube geometry as JSON, timestamps, JSON arguments.

#include <ctime>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/geometry_json.hpp"
#include "store_impl.hpp"

namespace geotandem::store::detail {

std::string utc_now() {
  std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

nlohmann::json parse_json_argument(const std::string& text, const std::string& what) {
  auto j = nlohmann::json::parse(text.empty() ? std::string("{}") : text, nullptr, false);
  if (j.is_discarded())
    throw InvalidArgument(what + " is not valid JSON: '" + text.substr(0, 80) + "'", {},
                          "pass a JSON object, e.g. {\"threshold\": 0.5}");
  return j;
}

nlohmann::json geometry_to_json(const volume::Geometry& g) {
  nlohmann::json j = volume::geometry_fields_json(g);
  j["shape"] = {g.shape[0], g.shape[1], g.shape[2]};
  return j;
}

volume::Geometry geometry_from_json(const nlohmann::json& j, const std::string& file) {
  try {
    volume::Geometry g;
    const auto& shape = j.at("shape");
    if (!shape.is_array() || shape.size() != 3) throw FormatError("geometry.shape must hold three integers", {file});
    for (int a = 0; a < 3; ++a)
      g.shape[a] = shape.at(a).get<std::int64_t>();
    g.inline0 = j.at("inline0").get<double>();
    g.inline_step = j.at("inline_step").get<double>();
    g.crossline0 = j.at("crossline0").get<double>();
    g.crossline_step = j.at("crossline_step").get<double>();
    g.z0 = j.at("z0").get<double>();
    g.dz = j.at("dz").get<double>();
    g.z_unit = volume::parse_sample_unit(j.at("z_unit").get<std::string>());
    const auto& a = j.at("affine");
    g.affine = {a.at("x0").get<double>(), a.at("xi").get<double>(), a.at("xj").get<double>(),
                a.at("y0").get<double>(), a.at("yi").get<double>(), a.at("yj").get<double>()};
    // Stores made before CRSs were kept have none: they open as "no CRS given".
    if (j.contains("crs")) g.crs = volume::crs_from_json(j.at("crs"));
    g.validate();
    return g;
  } catch (const nlohmann::json::exception& e) {
    throw FormatError(std::string("bad geometry: ") + e.what(), {file});
  } catch (const InvalidArgument& e) {
    throw FormatError("bad geometry: " + e.message(), {file});
  }
}

} // namespace geotandem::store::detail
