#include "frame.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "validate.hpp"

namespace geotandem::synth::detail {

Aabb Aabb::grown(double horizontal, double vertical) const {
  Aabb b = *this;
  const double d[3] = {horizontal, horizontal, vertical};
  for (int a = 0; a < 3; ++a) {
    b.lo[a] -= d[a];
    b.hi[a] += d[a];
  }
  return b;
}

bool Aabb::overlaps(const Aabb& other) const {
  for (int a = 0; a < 3; ++a)
    if (hi[a] < other.lo[a] || other.hi[a] < lo[a]) return false;
  return true;
}

volume::Box Aabb::samples(const volume::Box& clip) const {
  volume::Box box;
  for (int a = 0; a < 3; ++a) {
    // Clamp before converting so that huge boxes never overflow the integer range.
    const double below = static_cast<double>(clip.lo[a]) - 2.0, above = static_cast<double>(clip.hi[a]) + 1.0;
    const double first = std::clamp(std::ceil(lo[a]), below, above);
    const double last = std::clamp(std::floor(hi[a]), below, above);
    box.lo[a] = static_cast<std::int64_t>(first);
    box.hi[a] = static_cast<std::int64_t>(last) + 1;
  }
  return box.intersection(clip);
}

Frame::Frame(const SurveyOptions& survey, const volume::Index3& shape) {
  check_survey(survey);
  const double theta = survey.rotation_deg * std::numbers::pi / 180.0;
  const double s = std::sin(theta), c = std::cos(theta);
  geometry_.shape = shape;
  geometry_.inline0 = survey.inline0;
  geometry_.inline_step = 1.0;
  geometry_.crossline0 = survey.crossline0;
  geometry_.crossline_step = 1.0;
  geometry_.z0 = survey.z0;
  geometry_.dz = survey.dz;
  geometry_.z_unit = survey.z_unit;
  // Inline index i points to azimuth theta, crossline index j 90 degrees clockwise from it.
  auto& a = geometry_.affine;
  a.x0 = survey.x0;
  a.y0 = survey.y0;
  a.xi = survey.bin_inline_m * s;
  a.yi = survey.bin_inline_m * c;
  a.xj = survey.bin_crossline_m * c;
  a.yj = -survey.bin_crossline_m * s;
  geometry_.validate();

  const double det = a.xi * a.yj - a.xj * a.yi;
  unit_m_ = std::sqrt(std::abs(det));
  voxel_volume_world_ = std::abs(det) * survey.dz;
  m_ = {a.xi / unit_m_, a.xj / unit_m_, a.yi / unit_m_, a.yj / unit_m_};
  const double mdet = m_[0] * m_[3] - m_[1] * m_[2];
  n_ = {m_[3] / mdet, -m_[1] / mdet, -m_[2] / mdet, m_[0] / mdet};
  disc_ = {std::hypot(n_[0], n_[1]), std::hypot(n_[2], n_[3])};
}

std::array<double, 2> Frame::ellipse_extent(double a, double ux, double uy, double b, double vx, double vy) const {
  // The ellipse is {a*cos(t)*u + b*sin(t)*v}; its index image along i is
  // a*cos(t)*(N u)_i + b*sin(t)*(N v)_i, whose maximum is the norm of the two coefficients.
  const double ui = n_[0] * ux + n_[1] * uy, uj = n_[2] * ux + n_[3] * uy;
  const double vi = n_[0] * vx + n_[1] * vy, vj = n_[2] * vx + n_[3] * vy;
  return {std::hypot(a * ui, b * vi), std::hypot(a * uj, b * vj)};
}

std::array<double, 3> Frame::world(const Vec3& p) const {
  auto index = to_index(p);
  return geometry_.world(index[0], index[1], index[2]);
}

double axial_degrees(double azimuth_rad) {
  double deg = std::fmod(azimuth_rad * 180.0 / std::numbers::pi, 180.0);
  if (deg < 0.0) deg += 180.0;
  if (deg >= 180.0) deg -= 180.0;
  return deg;
}

} // namespace geotandem::synth::detail
