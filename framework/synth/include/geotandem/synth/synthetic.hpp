#pragma once
// Procedural synthetic cubes with ground truth. A synthetic cube is a Volume that computes any box
// on its own: every sample is a pure function of its global index, the seed and the options
// (counter-based hashing, no sequential random state), so a box read alone is bit-identical to the
// same box cut from the whole cube, whatever the order or the thread of the reads.
//
// Two kinds (docs/synthetic.md):
// - analytic: an attribute-like field in [0, 1] whose isosurface at GroundTruth::iso (0.5) is
//   exactly the surface of planted ellipsoids, sinuous tubes and a shell with a cavity, plus
//   thousands of bubbles; volumes and azimuths are known exactly.
// - seismic: a convolutional model (folded reflectivity * Ricker wavelet + band-limited noise)
//   with chaotic channels and lobes and a bright flat spot as negative control.

#include <memory>
#include <string>

#include "geotandem/synth/ground_truth.hpp"
#include "geotandem/synth/options.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::synth {

class SyntheticCube : public volume::Volume {
public:
  const volume::Geometry& geometry() const override { return truth_.geometry; }
  const GroundTruth& truth() const { return truth_; }
  std::string format() const override;
  std::string source() const override;
  // Thread safety: read() may be called from several threads at once (the cube is immutable).

protected:
  explicit SyntheticCube(GroundTruth truth) : truth_(std::move(truth)) {}
  GroundTruth truth_;
};

// The analytic iso value: bodies are {value >= analytic_iso}.
inline constexpr double analytic_iso = 0.5;

// Both throw InvalidArgument naming the bad option, its value and the valid range. Construction
// places the bodies (cost grows with the number of bodies and bubbles, not with the samples).
std::unique_ptr<SyntheticCube> make_analytic(const AnalyticOptions& options);
std::unique_ptr<SyntheticCube> make_seismic(const SeismicOptions& options);

} // namespace geotandem::synth
