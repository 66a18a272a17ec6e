// Layout of the seismic kind: the fold, then a channel through the centre, a lobe, a bright spot
// (negative control), a lobe cut by the border, then filler channels and lobes.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "hash.hpp"
#include "layout.hpp"
#include "seismic_model.hpp"

namespace geotandem::synth::detail {
namespace {

constexpr double gap_horizontal = 4.0; // traces between the boxes of two bodies

struct Sizes {
  double horizontal, vertical; // scale factors for small cubes
};

enum class Kind { channel, lobe, spot };

// Chaotic bodies at least 3/4 of a wavelet period thick (pi / sqrt(a) samples), or the wavelet's
// tails from the layers around them would dominate their interior.
double min_thickness(const Wavelet& wavelet) {
  return std::max(3.0, 0.75 * std::numbers::pi / std::sqrt(wavelet.a));
}

struct Candidate {
  std::variant<Channel, Lobe, BrightSpot> shape;
  Aabb bounds;
};

Candidate make(Kind kind, LayoutRng& rng, const Sizes& f, const std::array<double, 3>& index, double az,
               const Frame& frame, const Wavelet& wavelet, double spot_amplitude) {
  const Vec3 c = frame.to_frame(index[0], index[1], index[2]);
  const Axes axes = Axes::of(az);
  switch (kind) {
  case Kind::channel: {
    Channel ch;
    ch.half_width = std::max(2.5, f.horizontal * rng.uniform(4.0, 8.0));
    ch.depth = std::max(min_thickness(wavelet), f.vertical * rng.uniform(6.0, 12.0));
    const double wavelength = std::max(0.5, f.horizontal) * rng.uniform(40.0, 90.0);
    ch.line.centre = c;
    ch.line.azimuth = az;
    ch.line.axes = axes;
    ch.line.half_length = std::max(6.0, f.horizontal * rng.uniform(30.0, 60.0));
    ch.line.wavenumber = 2.0 * std::numbers::pi / wavelength;
    ch.line.amplitude = rng.uniform(0.6, 1.0) * SinuousLine::max_amplitude(wavelength, ch.half_width + 1.0);
    ch.line.phase = rng.uniform(0.0, 2.0 * std::numbers::pi);
    ch.line.prepare();
    ch.top = index[2] - 0.5 * ch.depth;
    ch.line.centre.z = ch.top;
    return {ch, ch.bounds(frame)};
  }
  case Kind::lobe: {
    Lobe lobe;
    lobe.a = std::max(4.0, f.horizontal * rng.uniform(10.0, 20.0));
    lobe.b = std::max(3.0, lobe.a * rng.uniform(0.4, 0.75));
    lobe.thickness = std::max(min_thickness(wavelet), f.vertical * rng.uniform(6.0, 12.0));
    lobe.azimuth = az;
    lobe.axes = axes;
    lobe.centre = c;
    lobe.centre.z = index[2] - 0.5 * lobe.thickness;
    return {lobe, lobe.bounds(frame)};
  }
  case Kind::spot: break;
  }
  BrightSpot spot;
  spot.a = std::max(4.0, f.horizontal * rng.uniform(8.0, 16.0));
  spot.b = std::max(3.0, spot.a * rng.uniform(0.4, 0.7));
  spot.azimuth = az;
  spot.axes = axes;
  spot.centre = c;
  spot.amplitude = spot_amplitude;
  return {spot, spot.bounds(frame, 0.5 * wavelet.half)};
}

std::optional<Candidate> place(LayoutRng& rng, Kind kind, Role role, const Sizes& sizes, int attempts, bool shrink,
                               const Frame& frame, const Wavelet& wavelet, double spot_amplitude, Packer& packer) {
  const auto& shape = frame.geometry().shape;
  for (int attempt = 0; attempt < attempts; ++attempt) {
    const double factor = shrink ? std::pow(0.85, attempt / 40) : 1.0;
    const Sizes f{sizes.horizontal * factor, sizes.vertical * factor};
    const double az = rng.uniform(0.0, std::numbers::pi);
    const std::uint64_t size_state = rng.next();
    LayoutRng probe_sizes(size_state);
    const Candidate probe = make(kind, probe_sizes, f, {0.0, 0.0, 0.0}, az, frame, wavelet, spot_amplitude);
    std::array<double, 3> half{};
    for (int a = 0; a < 3; ++a)
      half[a] = 0.5 * (probe.bounds.hi[a] - probe.bounds.lo[a]);
    const auto index = draw_centre(rng, role, shape, half);
    LayoutRng same_sizes(size_state);
    Candidate c = make(kind, same_sizes, f, index, az, frame, wavelet, spot_amplitude);
    if (!role_satisfied(role, c.bounds, index, shape) || !packer.fits(c.bounds)) continue;
    packer.add(c.bounds);
    return c;
  }
  return std::nullopt;
}

Fold make_fold(std::uint64_t seed, const Frame& frame, double spacing) {
  const auto& shape = frame.geometry().shape;
  LayoutRng rng(key(seed, Stream::fold));
  Fold fold;
  const double ni = static_cast<double>(shape[0]), nj = static_cast<double>(shape[1]);
  const int bumps = static_cast<int>(std::clamp(2.0 + ni * nj / (96.0 * 96.0), 2.0, 12.0));
  for (int n = 0; n < bumps; ++n) {
    const Vec3 at = frame.to_frame(rng.uniform(0.0, ni), rng.uniform(0.0, nj), 0.0);
    fold.bumps.push_back({at.x, at.y, rng.uniform(0.15, 0.35) * std::max(ni, nj), rng.uniform(0.03, 0.12)});
  }
  fold.dip_x = rng.uniform(-0.08, 0.08);
  fold.dip_y = rng.uniform(-0.08, 0.08);
  fold.offset = rng.uniform(0.0, 10.0 * spacing);
  return fold;
}

} // namespace

SeismicLayout layout_seismic(const SeismicOptions& options, const Frame& frame, const Wavelet& wavelet) {
  const auto& shape = frame.geometry().shape;
  SeismicLayout layout;
  layout.truth.kind = CubeKind::seismic;
  layout.truth.seed = options.seed;
  describe_frame(layout.truth, frame);
  layout.fold = make_fold(options.seed, frame, options.reflector_spacing);

  // Mean |amplitude| of layer spikes (uniform in [-1, 1]) is 0.5.
  const double spot_amplitude = 0.5 * options.bright_spot_gain;
  const Sizes sizes{std::clamp(static_cast<double>(std::min(shape[0], shape[1])) / 128.0, 0.25, 1.0),
                    std::clamp(static_cast<double>(shape[2]) / 128.0, 0.35, 1.0)};
  // Attributes smear bodies vertically by about a period of the wavelet (pi / sqrt(a) samples):
  // keep that much between them.
  const double gap_vertical = std::numbers::pi / std::sqrt(wavelet.a) + 2.0;
  const std::pair<Kind, Role> specials[] = {
      {Kind::channel, Role::centre}, {Kind::lobe, Role::free}, {Kind::spot, Role::free}, {Kind::lobe, Role::border}};
  const std::uint64_t layout_key = hash3(key(options.seed, Stream::layout), shape[0], shape[1], shape[2]);
  auto special = place_special_bodies<Candidate>(
      layout_key, std::size(specials), Packer(shape, gap_horizontal, gap_vertical),
      [&](LayoutRng& rng, Packer& packer, std::vector<Candidate>& placed) {
        for (auto [kind, role] : specials)
          if (auto c = place(rng, kind, role, sizes, 400, true, frame, wavelet, spot_amplitude, packer))
            placed.push_back(std::move(*c));
      });
  LayoutRng& rng = special.rng;
  Packer& packer = special.packer;

  int number = 0;
  double smallest = HUGE_VAL;
  auto accept = [&](Candidate c) {
    Body body;
    ++number;
    if (auto* ch = std::get_if<Channel>(&c.shape)) {
      Vec3 mid = ch->line.point(0.0);
      mid.z = ch->top + 0.5 * ch->depth;
      const double arc_length = ch->line.arc_length(); // 4097 slopes: once
      body = describe_body(frame, "channel-" + std::to_string(number), BodyType::channel, mid, ch->line.azimuth,
                           ch->volume(arc_length), c.bounds);
      body.dimensions = {{"half_width", ch->half_width},
                         {"depth", ch->depth},
                         {"half_length", ch->line.half_length},
                         {"amplitude", ch->line.amplitude},
                         {"wavelength", 2.0 * std::numbers::pi / ch->line.wavenumber},
                         {"phase", ch->line.phase},
                         {"arc_length", arc_length}};
      layout.chaotic.push_back(*ch);
    } else if (auto* lobe = std::get_if<Lobe>(&c.shape)) {
      Vec3 mid = lobe->centre;
      mid.z += 0.5 * lobe->thickness;
      body = describe_body(frame, "lobe-" + std::to_string(number), BodyType::lobe, mid, lobe->azimuth, lobe->volume(),
                           c.bounds);
      body.dimensions = {{"semi_axis_a", lobe->a}, {"semi_axis_b", lobe->b}, {"thickness", lobe->thickness}};
      layout.chaotic.push_back(*lobe);
    } else {
      const auto& spot = std::get<BrightSpot>(c.shape);
      // A reflector has no volume: count the main lobe of the wavelet (between its zero crossings,
      // sqrt(2 / a) samples) over the ellipse, which is roughly what an amplitude attribute lights.
      const double thickness = std::sqrt(2.0 / wavelet.a);
      body = describe_body(frame, "bright_spot-" + std::to_string(number), BodyType::bright_spot, spot.centre,
                           spot.azimuth, std::numbers::pi * spot.a * spot.b * thickness, c.bounds);
      body.volume_exact = false;
      body.negative_control = true;
      body.dimensions = {{"semi_axis_a", spot.a}, {"semi_axis_b", spot.b}, {"amplitude", spot.amplitude}};
      layout.spots.push_back(spot);
    }
    body.chaotic = !body.negative_control;
    if (body.chaotic && !body.cut_by_border) smallest = std::min(smallest, body.volume_voxels);
    layout.truth.bodies.push_back(std::move(body));
  };

  for (auto& c : special.placed)
    accept(std::move(c));

  const auto voxels = static_cast<double>(shape[0]) * static_cast<double>(shape[1]) * static_cast<double>(shape[2]);
  const auto fillers = static_cast<long>(std::llround(options.body_density * voxels / 1e6));
  int failures = 0;
  for (long n = 0; n < fillers && failures < 10; ++n) {
    auto c = place(rng, n % 2 ? Kind::lobe : Kind::channel, Role::free, sizes, 30, false, frame, wavelet,
                   spot_amplitude, packer);
    if (!c) {
      ++failures;
      continue;
    }
    failures = 0;
    accept(*c);
  }
  // Attribute components below a quarter of the smallest closed chaotic body are noise.
  layout.truth.bubble_volume_threshold_voxels = std::isfinite(smallest) ? std::max(20.0, 0.25 * smallest) : 20.0;
  return layout;
}

} // namespace geotandem::synth::detail
