#include "segy_coordinates.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "geotandem/core/error.hpp"

namespace geotandem::volume::detail::segy {

TraceCoordinates::TraceCoordinates(const TraceHeader& first, const SegyOptions& options, int trace,
                                   const std::string& path)
    : options_(options), first_scalar_(field(first, SEGY_TR_SOURCE_GROUP_SCALAR)),
      units_(field(first, SEGY_TR_COORD_UNITS)) {
  if (!geographic()) return;
  origin_ = scaled(first, trace, path);
  // WGS84: the meridian's radius of curvature M and the prime vertical's N at the first trace.
  constexpr double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f);
  const double phi = origin_[1] * std::numbers::pi / 180.0;
  const double w = 1.0 - e2 * std::sin(phi) * std::sin(phi);
  const double m = a * (1.0 - e2) / (w * std::sqrt(w)), n = a / std::sqrt(w);
  north_per_degree_ = m * std::numbers::pi / 180.0;
  east_per_degree_ = n * std::cos(phi) * std::numbers::pi / 180.0;
}

std::array<double, 2> TraceCoordinates::scaled(const TraceHeader& header, int trace, const std::string& path) const {
  const double scalar =
      options_.coordinate_scalar ? *options_.coordinate_scalar : field(header, SEGY_TR_SOURCE_GROUP_SCALAR);
  // Negative divides (as a product with 1/-scalar, which earlier versions used: same affines).
  const double factor = scalar == 0 ? 1.0 : scalar > 0 ? scalar : 1.0 / -scalar;
  const auto scale = [&](double v) { return v * factor; };
  std::array<double, 2> xy{scale(value(header, options_.x_field())), scale(value(header, options_.y_field()))};
  for (int n = 0; n < 2; ++n)
    if (!std::isfinite(xy[static_cast<std::size_t>(n)])) {
      const HeaderField f = n == 0 ? options_.x_field() : options_.y_field();
      throw FormatError("trace " + std::to_string(trace) + " holds a coordinate that is not a finite number (CDP " +
                            (n == 0 ? "X" : "Y") + ", trace header byte " + std::to_string(f.byte) + ", " +
                            to_string(f.type) + ")",
                        {path}, "check the byte and type of the coordinates (--x-byte, --x-type, ...)");
    }
  if (units_ == 2) {
    xy = {xy[0] / 3600.0, xy[1] / 3600.0};
  } else if (units_ == 4) {
    for (double& v : xy) { // +-DDDMMSS.ss
      const double d = std::floor(std::fabs(v) / 10000.0), m = std::floor((std::fabs(v) - d * 10000.0) / 100.0);
      const double sec = std::fabs(v) - d * 10000.0 - m * 100.0;
      v = std::copysign(d + m / 60.0 + sec / 3600.0, v);
    }
  }
  return xy;
}

std::array<double, 2> TraceCoordinates::xy(const TraceHeader& header, int trace, const std::string& path) const {
  const std::array<double, 2> xy = scaled(header, trace, path);
  if (!geographic()) return xy;
  return {(xy[0] - origin_[0]) * east_per_degree_, (xy[1] - origin_[1]) * north_per_degree_};
}

std::string TraceCoordinates::description() const {
  if (!geographic()) return "";
  static constexpr const char* names[] = {"seconds of arc", "decimal degrees", "degrees, minutes and seconds"};
  char origin[64];
  std::snprintf(origin, sizeof origin, "longitude %.6f, latitude %.6f", origin_[0], origin_[1]);
  return std::string(names[units_ - 2]) + " (byte 89 = " + std::to_string(units_) +
         "): longitude and latitude, taken as metres east and north of the first trace (" + origin +
         ") on the WGS84 ellipsoid; x and y are local, not map coordinates";
}

std::string TraceCoordinates::where() const {
  const auto at = [](const HeaderField& f) {
    return "byte " + std::to_string(f.byte) + " (" + to_string(f.type) + ")";
  };
  std::string text = "CDP X at " + at(options_.x_field()) + ", CDP Y at " + at(options_.y_field()) + "; ";
  const auto effect = [](int scalar) {
    return scalar == 0  ? std::string("0 means 1")
           : scalar > 0 ? "multiply by " + std::to_string(scalar)
                        : "divide by " + std::to_string(-static_cast<long long>(scalar));
  };
  if (options_.coordinate_scalar)
    return text + "scalar " + std::to_string(*options_.coordinate_scalar) + " given for every trace (" +
           effect(*options_.coordinate_scalar) + "; byte 71 ignored, " + std::to_string(first_scalar_) +
           " in the first trace)";
  return text + "scalar from byte 71 of each trace (" + std::to_string(first_scalar_) +
         " in the first trace: " + effect(first_scalar_) + ")";
}

} // namespace geotandem::volume::detail::segy
