#pragma once
// What was planted in a synthetic cube, written beside it as CUBE.truth.json. Index coordinates are
// fractional (i, j, k) with sample centres on integers; world coordinates go through the cube's
// survey affine (x east, y north in metres; z in the geometry's unit). Azimuths are world azimuths
// of a body's main horizontal axis, degrees clockwise from north, axial in [0, 180).

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "geotandem/volume/geometry.hpp"

namespace geotandem::synth {

enum class CubeKind { analytic, seismic };
const char* to_string(CubeKind kind);
// "analytic" or "seismic"; throws InvalidArgument otherwise.
CubeKind parse_cube_kind(const std::string& text);

enum class BodyType { ellipsoid, tube, shell, channel, lobe, bright_spot };
const char* to_string(BodyType type);

struct Body {
  std::string name; // unique in the cube, e.g. "tube-3"
  BodyType type = BodyType::ellipsoid;
  // Centre: ellipsoid, shell and lobe centre; midpoint of a tube's or channel's centre line (for a
  // channel at half its depth); bright spot centre. A shell's centre lies in its cavity.
  std::array<double, 3> centre_index{};
  std::array<double, 3> centre_world{};
  double azimuth_deg = 0.0; // main horizontal axis, [0, 180)
  // Volume of the whole body (also outside the cube when cut_by_border), in samples and in world
  // units (m^2*ms for time cubes, m^3 for depth cubes).
  double volume_voxels = 0.0;
  double volume_world = 0.0;
  bool volume_exact = true; // false for the bright spot (a reflector has no volume: an estimate)
  // Index-space box enclosing the body, fractional, may extend outside the cube.
  std::array<double, 3> bounds_lo{};
  std::array<double, 3> bounds_hi{};
  // Named shape parameters in body-frame units (horizontal: sqrt(bin area) metres, vertical:
  // samples), e.g. semi_axis_a, radius, wavelength. See docs/synthetic.md.
  std::vector<std::pair<std::string, double>> dimensions;
  bool crosses_block_plane = false; // straddles a plane at 1/4, 1/2 or 3/4 of some axis
  bool cut_by_border = false;       // reaches within one sample of the cube's border: not closed
  bool has_cavity = false;          // two surfaces (outer and inner)
  bool chaotic = false;             // chaotic reflectivity inside (seismic)
  bool negative_control = false;    // strong but continuous: an attribute should not select it
};

// Seismic-only facts.
struct SeismicTruth {
  double peak_frequency_hz = 0.0;
  double snr = 0.0;            // RMS(signal) / RMS(noise); infinity when there is no noise
  double signal_rms = 0.0;     // of the noiseless cube (estimated on a grid of traces)
  double noise_rms = 0.0;      // exact: signal_rms / snr
  double background_rms = 0.0; // noiseless signal away from chaotic bodies
  double chaotic_rms = 0.0;    // noiseless signal inside chaotic bodies
  int wavelet_half_length = 0; // samples each side of a spike that the wavelet reaches
  // A starting point for an RMS-amplitude attribute (window about one period): halfway, on a log
  // scale, between the background and chaotic RMS with noise added. Chaos attributes should be
  // thresholded on their own scale (see docs/synthetic.md).
  double rms_threshold_suggestion = 0.0;
};

struct GroundTruth {
  CubeKind kind = CubeKind::analytic;
  std::uint64_t seed = 0;
  volume::Geometry geometry;
  std::string world_volume_unit;   // "m2*ms" or "m3"
  double body_frame_unit_m = 0.0;  // metres per horizontal body-frame unit (sqrt of the bin area)
  double voxel_volume_world = 0.0; // world volume of one sample cell
  // Analytic: bodies are {value >= iso}. Seismic: empty (use the attribute suggestions).
  std::optional<double> iso;
  // Components below this volume are bubbles (noise); every planted body is far above it.
  double bubble_volume_threshold_voxels = 0.0;
  std::size_t bubble_count = 0;                            // analytic: tiny planted spheres, each one voxel component
  double bubble_radius_min = 0.0, bubble_radius_max = 0.0; // body-frame units
  std::array<std::vector<std::int64_t>, 3> block_planes;   // sample indices of the 1/4, 1/2, 3/4 planes
  std::vector<Body> bodies;
  std::optional<SeismicTruth> seismic;
};

nlohmann::json to_json(const GroundTruth& truth);
// Writes to_json(truth) to `path`; throws IoError naming the path when it cannot be written.
void write_ground_truth(const GroundTruth& truth, const std::string& path);
// Where the ground truth of a cube written at `cube_path` goes: cube_path + ".truth.json".
std::string truth_path_for(const std::string& cube_path);

} // namespace geotandem::synth
