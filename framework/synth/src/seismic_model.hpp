#pragma once
// Internals of the seismic kind: a convolutional model. Reflectivity is a layer cake of spikes in
// geological time, folded per trace (vertical stretch by Gaussian bumps plus a planar dip), with
// the spikes inside chaotic bodies replaced by random per-trace spikes of higher amplitude, and a
// flat bright reflector (negative control). Each spike is convolved analytically with a Ricker
// wavelet at its fractional position, so traces are smooth laterally and need no interpolation.

#include <cstdint>
#include <utility>
#include <variant>
#include <vector>

#include "frame.hpp"
#include "geotandem/synth/ground_truth.hpp"
#include "geotandem/synth/options.hpp"
#include "item_grid.hpp"
#include "shapes.hpp"

namespace geotandem::synth::detail {

// Ricker wavelet in samples: w(x) = (1 - 2 a x^2) exp(-a x^2), a = (pi f dt)^2, cut where
// exp(-a x^2) < 1e-7.
struct Wavelet {
  double a = 0.0;
  double half = 0.0;  // support half length (samples, fractional)
  double step2 = 0.0; // exp(-2 a) and exp(-32 a), the recurrences' steps (seismic_model.cpp)
  double step32 = 0.0;
  std::vector<double> taps; // w(n) for n = -floor(half) .. floor(half)

  Wavelet(double peak_frequency_hz, double dt_s);
  double operator()(double x) const;
  int half_taps() const { return static_cast<int>(taps.size() / 2); }
};

struct Bump {
  double x, y, sigma, height;
};

// Layer at geological time tau lies at sample tau * stretch(i, j) + shift(i, j).
struct Fold {
  std::vector<Bump> bumps;
  double dip_x = 0.0, dip_y = 0.0, offset = 0.0;
  void at(const Vec3& p, double& stretch, double& shift) const;
};

// A channel: flat top at `top`, U-shaped base top + depth (1 - (d / half_width)^2), d the
// horizontal distance to the sinuous centre line.
struct Channel {
  SinuousLine line;
  double half_width = 1.0, depth = 1.0, top = 0.0;
  // arc_length * 4/3 * half_width * depth (exact, see docs), with the line's arc length at hand.
  double volume(double arc_length) const;
  Aabb bounds(const Frame& frame) const;
};

// A lobe: horizontal ellipse, flat top at centre.z, base top + thickness (1 - rho^2).
struct Lobe {
  Vec3 centre;
  double a = 1.0, b = 1.0, thickness = 1.0, azimuth = 0.0;
  Axes axes;
  double volume() const; // pi a b thickness / 2
  Aabb bounds(const Frame& frame) const;
};

// A flat strong reflector over a horizontal ellipse, tapered at its rim.
struct BrightSpot {
  Vec3 centre;
  double a = 1.0, b = 1.0, azimuth = 0.0, amplitude = 1.0;
  Axes axes;
  double weight(const Vec3& p) const; // amplitude factor at a trace, 0 outside
  Aabb bounds(const Frame& frame, double half_height) const;
};

using Chaotic = std::variant<Channel, Lobe>;

// A sample range [top, base) of a trace inside a chaotic body.
struct Interval {
  double top, base;
};

// What a trace needs whatever samples of it are asked for: its chaotic intervals, fold and bright
// spots (position and weight).
struct TraceInfo {
  std::uint64_t model = 0; // SeismicModel::cache_id it was computed for (0: none)
  std::int64_t i = 0, j = 0;
  std::vector<Interval> inside;
  double stretch = 1.0, shift = 0.0;
  std::vector<std::pair<double, double>> spots; // (sample position, weight > 0)
};

struct SeismicModel {
  Frame frame;
  std::uint64_t reflector_key = 0, chaotic_key = 0, noise_key = 0;
  Wavelet wavelet;
  Fold fold;
  double spacing = 3.0;         // mean reflector spacing (samples)
  double chaotic_amplitude = 1; // half range of chaotic spike amplitudes (layers: 1)
  std::vector<Chaotic> chaotic;
  std::vector<BrightSpot> spots;
  ItemGrid chaotic_grid;    // per trace cell: chaotic bodies
  ItemGrid spot_grid;       // per trace cell: bright spots
  double noise_scale = 0.0; // multiplies unit-variance band-limited noise
  std::int64_t layer_m0 = 0;
  std::vector<double> layer_tau, layer_amplitude;

  SeismicModel(const Frame& frame, const Wavelet& wavelet);
  // Layer m's geological time and amplitude, from its hash; tabled for the layers a trace of an
  // unfolded cube crosses (table_layers()), computed again outside that range.
  void layer(std::int64_t m, double& tau, double& amplitude) const {
    const auto at = static_cast<std::uint64_t>(m - layer_m0);
    if (at < layer_tau.size()) {
      tau = layer_tau[at];
      amplitude = layer_amplitude[at];
    } else {
      compute_layer(m, tau, amplitude);
    }
  }
  void compute_layer(std::int64_t m, double& tau, double& amplitude) const;
  // Tables layers m0 .. m1 - 1 (after reflector_key and spacing are set; the values do not change).
  void table_layers(std::int64_t m0, std::int64_t m1);
  // Chaotic intervals of trace (i, j).
  void intervals(std::int64_t i, std::int64_t j, std::vector<Interval>& out) const;
  // Noiseless samples [k0, k1) of trace (i, j), written to out[0 .. k1 - k0).
  void trace(std::int64_t i, std::int64_t j, std::int64_t k0, std::int64_t k1, double* out) const;
  // The same with the trace's describe(i, j) at hand (what a caller reading several ranges of one
  // trace before the model is complete passes, instead of describing it again for every range).
  void trace(std::int64_t i, std::int64_t j, const TraceInfo& info, std::int64_t k0, std::int64_t k1,
             double* out) const;
  // The per-trace part of trace(), for trace (i, j).
  void describe(std::int64_t i, std::int64_t j, TraceInfo& out) const;

  // Set once the model is complete (make_seismic): trace() then keeps the per-trace part of recent
  // traces in a per-thread cache keyed by this id, since boxes stacked along the sample axis ask for
  // the same traces. 0: no caching (the model may still change). A model must not change after.
  std::uint64_t cache_id = 0;
  static std::uint64_t next_cache_id();
  // describe(i, j) through that cache (valid until this thread's next call).
  const TraceInfo& trace_info(std::int64_t i, std::int64_t j) const;
};

struct SeismicLayout {
  std::vector<Chaotic> chaotic;
  std::vector<BrightSpot> spots;
  Fold fold;
  GroundTruth truth;
};

// Places channels, lobes and the bright spot (deterministic in options.seed and options.shape).
SeismicLayout layout_seismic(const SeismicOptions& options, const Frame& frame, const Wavelet& wavelet);

} // namespace geotandem::synth::detail
