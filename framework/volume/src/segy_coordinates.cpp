#include "segy_coordinates.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace geotandem::volume::detail::segy {

TraceCoordinates::TraceCoordinates(const TraceHeader& first) : units_(field(first, SEGY_TR_COORD_UNITS)) {
  if (!geographic()) return;
  origin_ = scaled(first);
  // WGS84: the meridian's radius of curvature M and the prime vertical's N at the first trace.
  constexpr double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f);
  const double phi = origin_[1] * std::numbers::pi / 180.0;
  const double w = 1.0 - e2 * std::sin(phi) * std::sin(phi);
  const double m = a * (1.0 - e2) / (w * std::sqrt(w)), n = a / std::sqrt(w);
  north_per_degree_ = m * std::numbers::pi / 180.0;
  east_per_degree_ = n * std::cos(phi) * std::numbers::pi / 180.0;
}

std::array<double, 2> TraceCoordinates::scaled(const TraceHeader& header) const {
  const double scalar = field(header, SEGY_TR_SOURCE_GROUP_SCALAR);
  const double factor = scalar == 0 ? 1.0 : scalar > 0 ? scalar : 1.0 / -scalar;
  std::array<double, 2> xy{field(header, SEGY_TR_CDP_X) * factor, field(header, SEGY_TR_CDP_Y) * factor};
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

std::array<double, 2> TraceCoordinates::xy(const TraceHeader& header) const {
  const std::array<double, 2> xy = scaled(header);
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

} // namespace geotandem::volume::detail::segy
