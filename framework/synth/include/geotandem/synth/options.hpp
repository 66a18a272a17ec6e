#pragma once
// Parameters of the procedural synthetic cubes (see docs/synthetic.md). Every field has a default
// that gives a realistic cube; make_analytic and make_seismic validate them and throw
// InvalidArgument naming the field, its value and the valid range.

#include <cstdint>
#include <limits>

#include "geotandem/volume/box.hpp"
#include "geotandem/volume/geometry.hpp"

namespace geotandem::synth {

// Smallest accepted cube edge (samples) on every axis: below this the planted bodies cannot be
// placed with the separations the ground truth promises.
inline constexpr std::int64_t min_edge = 40;

// The survey the cube pretends to come from. The survey affine is orthogonal: increasing inline
// index i points to azimuth `rotation_deg` (clockwise from north), increasing crossline index j
// points 90 degrees clockwise from it. Bins need not be square.
struct SurveyOptions {
  double bin_inline_m = 25.0;    // distance between neighbouring inlines (m), > 0
  double bin_crossline_m = 25.0; // distance between neighbouring crosslines (m), > 0
  double rotation_deg = 30.0;    // azimuth of the inline-index axis (degrees), finite
  double dz = 4.0;               // sample interval in `z_unit`, > 0
  volume::SampleUnit z_unit = volume::SampleUnit::milliseconds;
  double z0 = 0.0;         // z of sample 0
  double x0 = 431250.0;    // world x (m, east) of trace (0, 0)
  double y0 = 6723100.0;   // world y (m, north) of trace (0, 0)
  double inline0 = 1000.0; // inline number of index 0 (step 1)
  double crossline0 = 2000.0;
};

// The analytic attribute-like field: values in [0, 1], bodies are {value >= analytic_iso}.
struct AnalyticOptions {
  volume::Index3 shape{128, 128, 128}; // every axis >= min_edge
  std::uint64_t seed = 1;
  SurveyOptions survey;
  // Planted bodies (ellipsoids and sinuous tubes) per million samples, on top of the four special
  // bodies every cube has (one crossing the mid-planes, one crossing a quarter-plane, one cut by the
  // border, one with a cavity). In [0, 200].
  double body_density = 20.0;
  // Tiny bubbles per million samples, in [0, 2000]. Fewer are planted where bodies leave no room.
  double bubble_density = 244.0;
};

// The convolutional seismic model: folded layer-cake reflectivity, Ricker wavelet, band-limited
// noise, chaotic channels and lobes, and a bright flat spot as a negative control.
struct SeismicOptions {
  volume::Index3 shape{128, 128, 128}; // every axis >= min_edge
  std::uint64_t seed = 1;
  SurveyOptions survey;            // z_unit must be milliseconds (the wavelet is defined in time)
  double peak_frequency_hz = 30.0; // Ricker peak frequency, in (0, Nyquist = 500 / dz_ms)
  // Signal-to-noise ratio as a ratio of RMS amplitudes (not dB), > 0; infinity: no noise.
  double snr = 4.0;
  // Chaotic bodies (channels and lobes) per million samples, on top of the special ones (one
  // channel through the centre, one lobe, one lobe cut by the border). In [0, 50].
  double body_density = 3.0;
  double chaotic_gain = 2.5;      // RMS reflectivity inside chaotic bodies / outside, in [1, 10]
  double bright_spot_gain = 4.0;  // bright spot amplitude / mean reflector amplitude, in [1, 20]
  double reflector_spacing = 3.0; // mean distance between reflectors (samples), in [1.5, 20]
};

} // namespace geotandem::synth
