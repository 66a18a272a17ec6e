#pragma once
// Where a post-stack SEG-Y file's traces are: their CDP coordinates as x and y (geographic units
// turned into local metres), and the affine fitted to every trace of a survey read header by
// header.

#include <array>
#include <cstdint>
#include <string>

#include "geotandem/volume/geometry.hpp"
#include "segy_grid.hpp"

namespace geotandem::volume::detail::segy {

// How the CDP coordinates of a file's traces (bytes 181/185 by default, or the fields SegyOptions
// declares, scaled by byte 71 or by the scalar SegyOptions gives: positive multiplies, negative
// divides, 0 means 1) become x and y, after the coordinate units of its first trace (byte 89). Lengths (1, and 0 for
// unspecified) are taken as written. Longitude and latitude (2: seconds of arc, 3: decimal degrees, 4: degrees, minutes
// and seconds written DDDMMSS) are taken as metres east and north of the first trace, by the WGS84 ellipsoid's radii of
// curvature at its latitude: across a survey of tens of kilometres the scale is off by a few parts in a million, so bin
// spacing and azimuths are right, but the coordinates are local, not those of a map projection.
class TraceCoordinates {
public:
  // `trace` and `path` name the trace in errors: a coordinate that is not finite (a float field
  // holding NaN) throws FormatError naming the file, the trace and the byte.
  TraceCoordinates(const TraceHeader& first, const SegyOptions& options, int trace = 0, const std::string& path = {});
  std::array<double, 2> xy(const TraceHeader& header, int trace, const std::string& path) const;
  bool geographic() const { return units_ >= 2 && units_ <= 4; }
  // For geographic units, what they are and how they were taken (a format detail); empty otherwise.
  std::string description() const;
  // Where the coordinates were read and how they were scaled, for `geotandem info`: "CDP X at byte
  // 181 (int32), CDP Y at byte 185 (int32); scalar from byte 71 (-100 in the first trace: divide by
  // 100)".
  std::string where() const;

private:
  // The coordinates as written, scaled: longitude and latitude in degrees when geographic.
  std::array<double, 2> scaled(const TraceHeader& header, int trace, const std::string& path) const;
  SegyOptions options_;
  int first_scalar_ = 0; // byte 71 of the first trace
  int units_ = 0;
  std::array<double, 2> origin_{}; // the first trace's longitude and latitude (degrees)
  double east_per_degree_ = 0.0, north_per_degree_ = 0.0;
};

// The least-squares fit of x = a + bu u + bv v (and y likewise) over traces at line-number offsets
// (u, v) from the first trace, coordinates taken from the first trace's too, so that the sums of
// products keep their precision.
class CoordinateFit {
public:
  void add(std::int64_t u, std::int64_t v, const std::array<double, 2>& xy) {
    if (n_ == 0) first_ = xy;
    any_ = any_ || xy[0] != 0.0 || xy[1] != 0.0;
    const double du = static_cast<double>(u), dv = static_cast<double>(v), dx = xy[0] - first_[0],
                 dy = xy[1] - first_[1];
    n_ += 1.0;
    su_ += du;
    sv_ += dv;
    suu_ += du * du;
    suv_ += du * dv;
    svv_ += dv * dv;
    sx_ = {sx_[0] + dx, sx_[1] + du * dx, sx_[2] + dv * dx};
    sy_ = {sy_[0] + dy, sy_[1] + du * dy, sy_[2] + dv * dy};
  }

  // The fit in grid indices: line numbers u = u0 + i u_step, v = v0 + j v_step (offsets from the
  // first trace's). The default grid at the first trace without coordinates or with every trace on
  // one line.
  SurveyAffine in_indices(double u0, double u_step, double v0, double v_step) const {
    SurveyAffine a;
    a.x0 = first_[0];
    a.y0 = first_[1];
    const double mu = su_ / n_, mv = sv_ / n_;
    const double vuu = suu_ - n_ * mu * mu, vuv = suv_ - n_ * mu * mv, vvv = svv_ - n_ * mv * mv;
    const double det = vuu * vvv - vuv * vuv;
    if (!any_ || !(det > 1e-9 * (vuu * vvv))) return a;
    // Centred on the means: the slopes from the 2 x 2 system; the value at (u0, v0) from the means.
    auto fit = [&](const std::array<double, 3>& s, double first, double& x0, double& along_i, double& along_j) {
      const double mean = s[0] / n_, cu = s[1] - n_ * mu * mean, cv = s[2] - n_ * mv * mean;
      const double bu = (cu * vvv - cv * vuv) / det, bv = (cv * vuu - cu * vuv) / det;
      x0 = first + mean + bu * (u0 - mu) + bv * (v0 - mv);
      along_i = bu * u_step;
      along_j = bv * v_step;
    };
    fit(sx_, first_[0], a.x0, a.xi, a.xj);
    fit(sy_, first_[1], a.y0, a.yi, a.yj);
    return a;
  }

private:
  std::array<double, 2> first_{};
  bool any_ = false;
  double n_ = 0.0, su_ = 0.0, sv_ = 0.0, suu_ = 0.0, suv_ = 0.0, svv_ = 0.0;
  std::array<double, 3> sx_{}, sy_{};
};

} // namespace geotandem::volume::detail::segy
