// Axial angles (orientations without a sense: 10 and 190 degrees are the same axis).

#include <cmath>
#include <numbers>
#include <string>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/measure.hpp"

namespace geotandem::mesh {

namespace {
constexpr double to_rad = std::numbers::pi / 180.0;

// Reduces an angle in degrees to [0, 180); rounding could otherwise leave exactly 180.
double reduce_axial(double deg) {
  double r = std::fmod(deg, 180.0);
  if (r < 0.0) r += 180.0;
  return r >= 180.0 ? 0.0 : r;
}
} // namespace

double axial_mean_deg(const std::vector<double>& azimuths_deg, const std::vector<double>& weights) {
  if (!weights.empty() && weights.size() != azimuths_deg.size())
    throw InvalidArgument("axial_mean_deg got " + std::to_string(azimuths_deg.size()) + " azimuths but " +
                              std::to_string(weights.size()) + " weights",
                          {}, "give one weight per azimuth, or none");
  // Doubling the angles turns axes into vectors whose sense means something; the mean vector's
  // angle halved is the mean axis.
  double s = 0.0, c = 0.0;
  for (std::size_t i = 0; i < azimuths_deg.size(); ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    s += w * std::sin(2.0 * azimuths_deg[i] * to_rad);
    c += w * std::cos(2.0 * azimuths_deg[i] * to_rad);
  }
  return reduce_axial(0.5 * std::atan2(s, c) / to_rad);
}

double axial_difference_deg(double a, double b) {
  const double d = reduce_axial(a - b);
  return d > 90.0 ? 180.0 - d : d;
}

} // namespace geotandem::mesh
