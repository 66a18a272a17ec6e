#pragma once
// The survey geometry of a synthetic cube and its body frame. Bodies are defined in the body
// frame: horizontal coordinates are world metres (relative to trace (0, 0)) divided by
// unit_m = sqrt(bin area), the vertical coordinate is the sample index. The frame keeps world
// azimuths (the horizontal scaling is isotropic) and has the volume of index space (its Jacobian
// is 1), so a body's volume in the frame is its volume in samples, and its world volume is that
// times the world volume of one sample cell.

#include <array>

#include "geotandem/synth/options.hpp"
#include "geotandem/volume/geometry.hpp"

namespace geotandem::synth::detail {

struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;
};

// Index-space box with fractional bounds (closed), possibly outside the cube.
struct Aabb {
  std::array<double, 3> lo{}, hi{};
  Aabb grown(double horizontal, double vertical) const;
  bool overlaps(const Aabb& other) const;
  // The samples inside, clipped to `clip` (empty when none).
  volume::Box samples(const volume::Box& clip) const;
};

class Frame {
public:
  // Throws InvalidArgument for a bad survey (non-positive bins or dz, non-finite values).
  Frame(const SurveyOptions& survey, const volume::Index3& shape);

  const volume::Geometry& geometry() const { return geometry_; }
  double unit_m() const { return unit_m_; }
  double voxel_volume_world() const { return voxel_volume_world_; }

  Vec3 to_frame(double i, double j, double k) const { return {m_[0] * i + m_[1] * j, m_[2] * i + m_[3] * j, k}; }
  std::array<double, 3> to_index(const Vec3& p) const {
    return {n_[0] * p.x + n_[1] * p.y, n_[2] * p.x + n_[3] * p.y, p.z};
  }
  // Index-space half extents (i, j) of a horizontal frame disc of radius 1.
  std::array<double, 2> disc_extent() const { return disc_; }
  // Index-space half extents (i, j) of the horizontal ellipse with semi-axes a along (ux, uy) and b
  // along (vx, vy) (unit frame vectors).
  std::array<double, 2> ellipse_extent(double a, double ux, double uy, double b, double vx, double vy) const;

  std::array<double, 3> world(const Vec3& p) const;

private:
  volume::Geometry geometry_;
  double unit_m_ = 1.0;
  double voxel_volume_world_ = 1.0;
  std::array<double, 4> m_{}; // index (i, j) -> frame (x, y), row major
  std::array<double, 4> n_{}; // its inverse
  std::array<double, 2> disc_{};
};

// Azimuth in degrees, reduced to the axial range [0, 180).
double axial_degrees(double azimuth_rad);

} // namespace geotandem::synth::detail
