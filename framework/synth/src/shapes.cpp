#include "shapes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace geotandem::synth::detail {

Axes Axes::of(double azimuth_rad) {
  const double s = std::sin(azimuth_rad), c = std::cos(azimuth_rad);
  return {s, c, c, -s};
}

Ellipsoid::Ellipsoid(Vec3 centre_in, double a_in, double b_in, double c_in, double azimuth_in)
    : centre(centre_in), a(a_in), b(b_in), c(c_in), azimuth(azimuth_in), axes(Axes::of(azimuth_in)) {}

Ellipsoid::Column Ellipsoid::column(const Vec3& p) const {
  const double dx = p.x - centre.x, dy = p.y - centre.y;
  const double s = (dx * axes.ux + dy * axes.uy) / a;
  const double n = (dx * axes.vx + dy * axes.vy) / b;
  return {s * s + n * n, s * s / (a * a) + n * n / (b * b)};
}

double Ellipsoid::signed_distance(const Column& column, double at_z) const {
  const double z = (at_z - centre.z) / c;
  const double rho = std::sqrt(column.rho2 + z * z);
  // |grad rho| * rho = |(s/a, n/b, z/c)| in normalised coordinates.
  const double g = std::sqrt(column.grad2 + z * z / (c * c));
  if (g == 0.0) return std::min({a, b, c});
  return (1.0 - rho) * rho / g;
}

double Ellipsoid::volume() const {
  return 4.0 / 3.0 * std::numbers::pi * a * b * c;
}

Aabb Ellipsoid::bounds(const Frame& frame) const {
  auto e = frame.ellipse_extent(a, axes.ux, axes.uy, b, axes.vx, axes.vy);
  auto ci = frame.to_index(centre);
  return Aabb{{ci[0] - e[0], ci[1] - e[1], ci[2] - c}, {ci[0] + e[0], ci[1] + e[1], ci[2] + c}};
}

Shell::Shell(const Ellipsoid& outer_in, double inner_in)
    : outer(outer_in),
      cavity(outer_in.centre, outer_in.a * inner_in, outer_in.b * inner_in, outer_in.c * inner_in, outer_in.azimuth),
      inner(inner_in) {}

double Shell::signed_distance(const Column& column, double z) const {
  return std::min(outer.signed_distance(column.outer, z), -cavity.signed_distance(column.cavity, z));
}

double Shell::volume() const {
  return outer.volume() * (1.0 - inner * inner * inner);
}

double Sphere::signed_distance(const Column& column, double z) const {
  const double dz = z - centre.z;
  return r - std::sqrt(column.horizontal2 + dz * dz);
}

double SinuousLine::offset(double t) const {
  return amplitude * std::sin(wavenumber * t + phase);
}

double SinuousLine::slope(double t) const {
  return amplitude * wavenumber * std::cos(wavenumber * t + phase);
}

Vec3 SinuousLine::point(double t) const {
  const double n = offset(t);
  return {centre.x + t * axes.ux + n * axes.vx, centre.y + t * axes.uy + n * axes.vy, centre.z};
}

void SinuousLine::local(const Vec3& p, double& s, double& n) const {
  const double dx = p.x - centre.x, dy = p.y - centre.y;
  s = dx * axes.ux + dy * axes.uy;
  n = dx * axes.vx + dy * axes.vy;
}

double SinuousLine::nearest(double s, double n) const {
  // Root of g'(t)/2 = (t - s) + (h(t) - n) h'(t), increasing in t under the convexity condition.
  // It lies within |t - s| <= (A + |n|) A k; safeguarded Newton inside that bracket.
  const double bracket = (amplitude + std::abs(n)) * amplitude * wavenumber + 1e-9;
  double lo = s - bracket, hi = s + bracket, t = s;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double arg = wavenumber * t + phase;
    const double sn = std::sin(arg), cs = std::cos(arg);
    const double h = amplitude * sn, h1 = amplitude * wavenumber * cs;
    const double h2 = -amplitude * wavenumber * wavenumber * sn;
    const double f = (t - s) + (h - n) * h1;
    const double df = 1.0 + h1 * h1 + (h - n) * h2;
    if (f == 0.0) break;
    if (f < 0.0)
      lo = t;
    else
      hi = t;
    double next = t - f / df;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    // The distance is stationary at the root: an error e in t changes it by O(e^2).
    if (std::abs(next - t) <= 1e-8) {
      t = next;
      break;
    }
    t = next;
  }
  return t;
}

void SinuousLine::prepare() {
  for (int e = 0; e < 2; ++e) {
    const double t = e == 0 ? -half_length : half_length;
    const double h1 = slope(t), norm = std::sqrt(1.0 + h1 * h1);
    end_n[e] = offset(t);
    end_ts[e] = 1.0 / norm;
    end_tn[e] = h1 / norm;
  }
  const double lip = amplitude * wavenumber;
  lipschitz_factor = 1.0 / std::sqrt(1.0 + lip * lip);
}

double SinuousLine::end_distance(double s, double n) const {
  const double first = (s + half_length) * end_ts[0] + (n - end_n[0]) * end_tn[0];
  const double last = (half_length - s) * end_ts[1] - (n - end_n[1]) * end_tn[1];
  return std::min(first, last);
}

double SinuousLine::arc_length() const {
  // Composite Simpson rule on sqrt(1 + h'(t)^2); the integrand is smooth and periodic, so 4096
  // intervals leave an error far below 1e-9 of the length.
  constexpr int intervals = 4096;
  const double step = 2.0 * half_length / intervals;
  auto f = [&](double t) {
    const double h1 = slope(t);
    return std::sqrt(1.0 + h1 * h1);
  };
  double sum = f(-half_length) + f(half_length);
  for (int n = 1; n < intervals; ++n)
    sum += (n % 2 ? 4.0 : 2.0) * f(-half_length + n * step);
  return sum * step / 3.0;
}

Aabb SinuousLine::bounds(const Frame& frame, double radius_h, double radius_v) const {
  // The body lies within the union of balls of radius `radius_h` centred on the line: sample the
  // line densely and grow by the index extent of such a ball (plus the sagitta between samples).
  constexpr int samples = 128;
  Aabb box{{HUGE_VAL, HUGE_VAL, HUGE_VAL}, {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}};
  for (int n = 0; n <= samples; ++n) {
    auto index = frame.to_index(point(-half_length + 2.0 * half_length * n / samples));
    for (int a = 0; a < 2; ++a) {
      box.lo[a] = std::min(box.lo[a], index[a]);
      box.hi[a] = std::max(box.hi[a], index[a]);
    }
  }
  const double step = 2.0 * half_length / samples;
  const double sagitta = amplitude * wavenumber * wavenumber * step * step / 8.0 + 1e-9;
  auto disc = frame.disc_extent();
  for (int a = 0; a < 2; ++a) {
    box.lo[a] -= (radius_h + sagitta) * disc[a];
    box.hi[a] += (radius_h + sagitta) * disc[a];
  }
  box.lo[2] = centre.z - radius_v;
  box.hi[2] = centre.z + radius_v;
  return box;
}

double SinuousLine::max_amplitude(double wavelength, double reach) {
  // Largest A with A k^2 (2A + reach) = 0.9: 2k^2 A^2 + k^2 reach A - 0.9 = 0.
  const double k = 2.0 * std::numbers::pi / wavelength, k2 = k * k;
  return (-k2 * reach + std::sqrt(k2 * k2 * reach * reach + 7.2 * k2)) / (4.0 * k2);
}

// Only samples closer than radius + band to the line can get an estimate above -band; all others
// get -reach. Cheap tests first: no point of the line has |n| > A, its ends lie at
// |s| <= half_length, and (the line being the graph of a Lipschitz function of s) the distance is
// at least the offset across it times 1/sqrt(1 + L^2). The nearest point comes last, once per
// column and only when a sample passes those tests.
Tube::Column Tube::column(const Vec3& p) const {
  Column c;
  line.local(p, c.s, c.n);
  const double near = radius + band;
  if (std::abs(c.n) > line.amplitude + near || std::abs(c.s) > line.half_length + radius + reach) return c;
  c.far = false;
  const double across = std::abs(c.n - line.offset(c.s)) * line.lipschitz_factor;
  c.across2 = across * across;
  return c;
}

double Tube::signed_distance(Column& c, double z) const {
  const double dz = z - line.centre.z;
  const double near = radius + band;
  if (c.far || std::abs(dz) > near) return -reach;
  if (c.across2 + dz * dz > near * near) return -reach;
  if (!c.nearest) {
    const double t = line.nearest(c.s, c.n);
    const double ds = c.s - t, dn = c.n - line.offset(t);
    c.horizontal2 = ds * ds + dn * dn;
    c.end = line.end_distance(c.s, c.n);
    c.nearest = true;
  }
  const double d = std::sqrt(c.horizontal2 + dz * dz);
  return std::min(radius - d, c.end);
}

double Tube::volume() const {
  return line.arc_length() * std::numbers::pi * radius * radius;
}

} // namespace geotandem::synth::detail
