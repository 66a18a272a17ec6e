#pragma once
// Body shapes in the body frame (frame.hpp). Each solid shape gives a signed distance estimate
// (positive inside) whose zero set is exactly the shape's surface and which is close to the true
// distance near it; the analytic field is a smooth profile of it, so the isosurface at the iso value
// is exactly the planted surface.

#include "frame.hpp"

namespace geotandem::synth::detail {

// Horizontal frame directions of an azimuth (radians, clockwise from north): u along it, v 90
// degrees clockwise from u.
struct Axes {
  double ux = 0.0, uy = 1.0, vx = 1.0, vy = 0.0;
  static Axes of(double azimuth_rad);
};

struct Ellipsoid {
  Vec3 centre;
  double a = 1.0, b = 1.0, c = 1.0; // semi-axes: along the azimuth, across it, vertical
  double azimuth = 0.0;             // radians
  Axes axes;

  Ellipsoid(Vec3 centre, double a, double b, double c, double azimuth);
  double volume() const;
  Aabb bounds(const Frame& frame) const;

  // (1 - rho) / |grad rho| with rho the normalised radius: exact sign, first-order distance. Every
  // shape's distance is taken a column of samples at a time (the analytic kind reads boxes): its
  // terms that depend on x and y alone once per column (column()), then one sample's
  // (signed_distance(column, z)).
  struct Column {
    double rho2 = 0.0, grad2 = 0.0; // the horizontal terms of rho^2 and of |grad rho|^2 rho^2
  };
  Column column(const Vec3& p) const;
  double signed_distance(const Column& column, double z) const;
  double signed_distance(const Vec3& p) const { return signed_distance(column(p), p.z); }
};

// A thick ellipsoidal shell: the outer ellipsoid minus the same ellipsoid scaled by `inner`.
struct Shell {
  Ellipsoid outer;
  Ellipsoid cavity;
  double inner = 0.5;

  Shell(const Ellipsoid& outer, double inner);
  double volume() const;
  Aabb bounds(const Frame& frame) const { return outer.bounds(frame); }

  struct Column {
    Ellipsoid::Column outer, cavity;
  };
  Column column(const Vec3& p) const { return {outer.column(p), cavity.column(p)}; }
  double signed_distance(const Column& column, double z) const;
  double signed_distance(const Vec3& p) const { return signed_distance(column(p), p.z); }
};

// A bubble.
struct Sphere {
  Vec3 centre;
  double r = 1.0;

  struct Column {
    double horizontal2 = 0.0;
  };
  Column column(const Vec3& p) const {
    const double dx = p.x - centre.x, dy = p.y - centre.y;
    return {dx * dx + dy * dy};
  }
  double signed_distance(const Column& column, double z) const;
  double signed_distance(const Vec3& p) const { return signed_distance(column(p), p.z); }
};

// A horizontal sinuous centre line: c(t) = centre + t*u + A*sin(k*t + phase)*v, t in
// [-half_length, half_length]. The nearest point of a point within `reach` of the line is unique
// when A*k^2*(2A + reach) < 1 (the squared distance is then convex in t); max_amplitude() gives
// amplitudes that keep a margin below that bound.
struct SinuousLine {
  Vec3 centre;
  double azimuth = 0.0;
  Axes axes;
  double half_length = 1.0;
  double amplitude = 0.0;
  double wavenumber = 1.0; // 2*pi / wavelength
  double phase = 0.0;

  double offset(double t) const;
  double slope(double t) const;
  Vec3 point(double t) const;
  // Local horizontal coordinates (s along u, n along v) of a frame point.
  void local(const Vec3& p, double& s, double& n) const;
  // Parameter of the nearest point of the infinite line to local (s, n) (|n| <= A + reach).
  double nearest(double s, double n) const;
  // Signed distances to the end planes (normal planes at t = -half_length and +half_length),
  // positive between them; min of the two. Call prepare() after changing the line.
  double end_distance(double s, double n) const;
  void prepare();
  double arc_length() const;
  Aabb bounds(const Frame& frame, double radius_h, double radius_v) const;

  static double max_amplitude(double wavelength, double reach);

  // End points and unit tangents (local coordinates), set by prepare().
  double end_n[2] = {0.0, 0.0}, end_ts[2] = {1.0, 1.0}, end_tn[2] = {0.0, 0.0};
  double lipschitz_factor = 1.0; // 1 / sqrt(1 + (A k)^2)
};

// The points within `radius` of a sinuous line, with flat ends. Its volume is exactly
// arc_length * pi * radius^2 (tube formula; needs radius below the line's curvature radius, which
// max_amplitude guarantees).
struct Tube {
  SinuousLine line;
  double radius = 1.0;
  double band = 1.0;  // estimates are exact-signed first-order distances down to -band
  double reach = 2.0; // returned (negated) where the estimate is below -band; reach >= band

  double volume() const;
  Aabb bounds(const Frame& frame) const { return line.bounds(frame, radius, radius); }

  // The line is horizontal: what the distance needs of p.x and p.y alone, for a column of samples.
  struct Column {
    bool far = true;          // every sample of the column is farther than radius + band
    double s = 0.0, n = 0.0;  // the column in the line's local coordinates
    double across2 = 0.0;     // squared lower bound on the horizontal distance to the line
    bool nearest = false;     // whether the two below are known (once a sample needs them):
    double horizontal2 = 0.0; // squared horizontal distance to the line's nearest point
    double end = 0.0;         // the distance estimate to the line's ends
  };
  Column column(const Vec3& p) const;
  double signed_distance(Column& column, double z) const;
  double signed_distance(const Vec3& p) const {
    Column c = column(p);
    return signed_distance(c, p.z);
  }
};

} // namespace geotandem::synth::detail
