// Layout of the analytic kind: four special bodies (a shell with a cavity, an ellipsoid across the
// three mid-planes, a tube across an inline quarter-plane, an ellipsoid cut by the border), filler
// ellipsoids and tubes, then bubbles on a jittered lattice wherever bodies leave room.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "analytic.hpp"
#include "layout.hpp"

namespace geotandem::synth::detail {
namespace {

constexpr double gap = 3.0;          // samples between the boxes of two bodies
constexpr std::int64_t lattice = 8;  // bubble lattice cell (samples)
constexpr double bubble_r_min = 0.6; // body-frame units
constexpr double bubble_r_max = 1.2;
constexpr double tube_reach = 3.0 * transition_width + 1.0;

struct Candidate {
  Item item;
  BodyType type;
  Vec3 centre;
  double azimuth;
  Aabb bounds;
  double influence; // growth of the bounds (body-frame units) beyond which the field is background
};

// A shape drawn at the frame origin, to know its extents before choosing its centre.
using Maker = Candidate (*)(LayoutRng&, double scale, const Vec3& centre, double azimuth, const Frame&);

Candidate make_ellipsoid(LayoutRng& rng, double f, const Vec3& c, double az, const Frame& frame) {
  const double a = std::max(5.0, f * rng.uniform(7.0, 16.0));
  const double b = std::max(3.0, a * rng.uniform(0.35, 0.7));
  const double h = std::max(2.5, f * rng.uniform(3.0, 6.0));
  Ellipsoid e(c, a, b, h, az);
  const double ratio = std::max({a, b, h}) / std::min({a, b, h});
  return {e, BodyType::ellipsoid, c, az, e.bounds(frame), transition_width * ratio + 1.0};
}

Candidate make_shell(LayoutRng& rng, double f, const Vec3& c, double az, const Frame& frame) {
  constexpr double inner = 0.45; // the thinnest wall, c * 0.55, stays above 3 samples
  const double a = std::max(6.5, f * rng.uniform(9.0, 12.0));
  const double b = a * rng.uniform(0.75, 0.9);
  const double h = std::max(5.5, f * rng.uniform(6.0, 8.0));
  Shell s(Ellipsoid(c, a, std::max(b, h), h, az), inner);
  const double ratio = s.outer.a / s.outer.c;
  return {s, BodyType::shell, c, az, s.bounds(frame), transition_width * ratio + 1.0};
}

Candidate make_tube(LayoutRng& rng, double f, const Vec3& c, double az, const Frame& frame) {
  Tube t;
  t.radius = std::max(2.0, f * rng.uniform(2.5, 4.0));
  t.band = transition_width;
  t.reach = tube_reach;
  const double wavelength = rng.uniform(36.0, 64.0);
  t.line.centre = c;
  t.line.azimuth = az;
  t.line.axes = Axes::of(az);
  t.line.half_length = std::max(8.0, f * rng.uniform(15.0, 35.0));
  t.line.wavenumber = 2.0 * std::numbers::pi / wavelength;
  t.line.amplitude = rng.uniform(0.6, 1.0) * SinuousLine::max_amplitude(wavelength, t.radius + transition_width + 1.0);
  t.line.phase = rng.uniform(0.0, 2.0 * std::numbers::pi);
  t.line.prepare();
  return {t, BodyType::tube, t.line.point(0.0), az, t.bounds(frame), tube_reach};
}

// Volume (samples) and named dimensions of an accepted body (the tube's arc length is too costly
// to compute for every rejected attempt).
std::pair<double, std::vector<std::pair<std::string, double>>> measure(const Item& item) {
  if (const auto* e = std::get_if<Ellipsoid>(&item))
    return {e->volume(), {{"semi_axis_a", e->a}, {"semi_axis_b", e->b}, {"semi_axis_c", e->c}}};
  if (const auto* s = std::get_if<Shell>(&item))
    return {s->volume(),
            {{"semi_axis_a", s->outer.a},
             {"semi_axis_b", s->outer.b},
             {"semi_axis_c", s->outer.c},
             {"inner_scale", s->inner}}};
  const auto& t = std::get<Tube>(item);
  return {t.volume(),
          {{"radius", t.radius},
           {"half_length", t.line.half_length},
           {"amplitude", t.line.amplitude},
           {"wavelength", 2.0 * std::numbers::pi / t.line.wavenumber},
           {"phase", t.line.phase},
           {"arc_length", t.line.arc_length()}}};
}

// Tries to place one body of `role`; shrinks it after repeated failures when `shrink`.
std::optional<Candidate> place(LayoutRng& rng, Maker make, Role role, double scale, int attempts, bool shrink,
                               const Frame& frame, Packer& packer) {
  const auto& shape = frame.geometry().shape;
  for (int attempt = 0; attempt < attempts; ++attempt) {
    const double f = shrink ? scale * std::pow(0.9, attempt / 40) : scale;
    const double az = rng.uniform(0.0, std::numbers::pi);
    const std::uint64_t size_state = rng.next();
    LayoutRng sizes(size_state);
    Candidate probe = make(sizes, f, Vec3{}, az, frame);
    std::array<double, 3> half{};
    for (int a = 0; a < 3; ++a)
      half[a] = 0.5 * (probe.bounds.hi[a] - probe.bounds.lo[a]);
    auto index = draw_centre(rng, role, shape, half);
    LayoutRng same_sizes(size_state);
    Candidate c = make(same_sizes, f, frame.to_frame(index[0], index[1], index[2]), az, frame);
    if (!role_satisfied(role, c.bounds, index, shape) || !packer.fits(c.bounds)) continue;
    packer.add(c.bounds);
    return c;
  }
  return std::nullopt;
}

void add_body(AnalyticLayout& layout, const Frame& frame, Candidate c, int number) {
  const auto cube = frame.geometry().bounds();
  auto disc = frame.disc_extent();
  Aabb reach = c.bounds;
  for (int a = 0; a < 2; ++a) {
    reach.lo[a] -= c.influence * disc[a];
    reach.hi[a] += c.influence * disc[a];
  }
  reach.lo[2] -= c.influence;
  reach.hi[2] += c.influence;
  auto [volume, dimensions] = measure(c.item);
  Body body = describe_body(frame, std::string(to_string(c.type)) + "-" + std::to_string(number), c.type, c.centre,
                            c.azimuth, volume, c.bounds);
  body.has_cavity = c.type == BodyType::shell;
  body.dimensions = std::move(dimensions);
  layout.truth.bodies.push_back(std::move(body));
  layout.items.push_back(std::move(c.item));
  layout.influence.push_back(reach.samples(cube));
}

void add_bubbles(AnalyticLayout& layout, const AnalyticOptions& options, const Frame& frame, const Packer& packer) {
  const auto& shape = frame.geometry().shape;
  const auto disc = frame.disc_extent();
  const auto cube = frame.geometry().bounds();
  // A bubble reaches at most `reach` samples from its centre along each axis (more along the
  // shorter bin). Centres sit on samples, `margin` to cell - margin - 1 into lattice cells of
  // `cell` samples: bubbles of neighbouring cells keep at least two empty samples between them,
  // and each bubble holds at least its centre sample.
  std::array<std::int64_t, 3> reach{}, margin{}, cell{};
  double cell_volume = 1.0;
  for (int a = 0; a < 3; ++a) {
    reach[a] = static_cast<std::int64_t>(std::floor(bubble_r_max * (a < 2 ? disc[a] : 1.0)));
    margin[a] = reach[a] + 1;
    cell[a] = std::max(lattice, 2 * margin[a] + 4);
    cell_volume *= static_cast<double>(cell[a]);
  }
  const double keep = std::min(1.0, options.bubble_density * cell_volume / 1e6);
  const std::uint64_t k = key(options.seed, Stream::bubbles);
  std::size_t count = 0;
  for (std::int64_t ci = 0; ci * cell[0] < shape[0]; ++ci)
    for (std::int64_t cj = 0; cj * cell[1] < shape[1]; ++cj)
      for (std::int64_t ck = 0; ck * cell[2] < shape[2]; ++ck) {
        std::uint64_t h = hash3(k, ci, cj, ck);
        if (unit(h) >= keep) continue;
        const std::int64_t index[3] = {ci, cj, ck};
        std::array<std::int64_t, 3> centre{};
        bool inside = true;
        for (int a = 0; a < 3; ++a) {
          h = mix64(h);
          const auto span = static_cast<std::uint64_t>(cell[a] - 2 * margin[a]);
          centre[a] = index[a] * cell[a] + margin[a] + static_cast<std::int64_t>(h % span);
          inside = inside && centre[a] <= shape[a] - 1 - margin[a];
        }
        if (!inside) continue;
        const double r = uniform(mix64(h), bubble_r_min, bubble_r_max);
        Sphere sphere{frame.to_frame(static_cast<double>(centre[0]), static_cast<double>(centre[1]),
                                     static_cast<double>(centre[2])),
                      r};
        const double ext[3] = {r * disc[0], r * disc[1], r};
        Aabb box;
        for (int a = 0; a < 3; ++a) {
          box.lo[a] = static_cast<double>(centre[a]) - ext[a];
          box.hi[a] = static_cast<double>(centre[a]) + ext[a];
        }
        if (packer.near_any(box)) continue;
        layout.items.push_back(sphere);
        layout.influence.push_back(
            box.grown(transition_width * std::max(disc[0], disc[1]) + 1.0, transition_width + 1.0).samples(cube));
        ++count;
      }
  layout.truth.bubble_count = count;
}

} // namespace

AnalyticLayout layout_analytic(const AnalyticOptions& options, const Frame& frame) {
  const auto& shape = frame.geometry().shape;
  AnalyticLayout layout;
  layout.truth.kind = CubeKind::analytic;
  layout.truth.seed = options.seed;
  describe_frame(layout.truth, frame);
  layout.truth.iso = 0.5;
  layout.truth.bubble_volume_threshold_voxels = analytic_bubble_threshold;
  layout.truth.bubble_radius_min = bubble_r_min;
  layout.truth.bubble_radius_max = bubble_r_max;

  const double scale = std::clamp(static_cast<double>(std::min({shape[0], shape[1], shape[2]})) / 96.0, 0.4, 1.0);
  const std::pair<Maker, Role> specials[] = {{make_shell, Role::free},
                                             {make_ellipsoid, Role::centre},
                                             {make_tube, Role::quarter_plane},
                                             {make_ellipsoid, Role::border}};
  const std::uint64_t layout_key = hash3(key(options.seed, Stream::layout), shape[0], shape[1], shape[2]);
  auto special =
      place_special_bodies<Candidate>(layout_key, std::size(specials), Packer(shape, gap, gap),
                                      [&](LayoutRng& rng, Packer& packer, std::vector<Candidate>& placed) {
                                        for (auto [maker, role] : specials)
                                          if (auto c = place(rng, maker, role, scale, 400, true, frame, packer))
                                            placed.push_back(std::move(*c));
                                      });
  LayoutRng& rng = special.rng;
  Packer& packer = special.packer;
  int number = 0;
  for (auto& c : special.placed)
    add_body(layout, frame, std::move(c), ++number);

  const auto voxels = static_cast<double>(shape[0]) * static_cast<double>(shape[1]) * static_cast<double>(shape[2]);
  const auto fillers = static_cast<long>(std::llround(options.body_density * voxels / 1e6));
  int failures = 0;
  for (long n = 0; n < fillers && failures < 10; ++n) {
    auto c = place(rng, n % 2 ? make_tube : make_ellipsoid, Role::free, scale, 30, false, frame, packer);
    if (!c) {
      ++failures;
      continue;
    }
    failures = 0;
    add_body(layout, frame, std::move(*c), ++number);
  }
  add_bubbles(layout, options, frame, packer);
  return layout;
}

} // namespace geotandem::synth::detail
