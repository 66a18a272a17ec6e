#pragma once
// Normalise: the input divided by a scale, so that attributes of different units can be combined
// (chaos x normalised envelope for "chaotic and high amplitude").
//
// method "percentile" (default): the scale is the given percentile (nearest rank) of |input| over
// a deterministic sample of the cube: a regular grid of up to sample_boxes^3 boxes of edge
// sample_edge (clipped to the cube), spread evenly from face to face. The sample does not depend on
// which box is read first, so every box, and every worker, divides by the same number. It is
// computed once, on the first read or the first call to scale().
// method "fixed": the scale is the `scale` parameter.
// No halo of its own.

#include <mutex>

#include "geotandem/attributes/attribute.hpp"
#include "geotandem/attributes/params.hpp"

namespace geotandem::attributes {

enum class ScaleMethod { percentile, fixed };
const char* to_string(ScaleMethod method);

struct NormaliseOptions : DeclaredOptions<NormaliseOptions> {
  ScaleMethod method = ScaleMethod::percentile;
  double percentile = 99.0; // percent, of |input|
  double scale = 1.0;       // the divisor when method is fixed
  int sample_boxes = 4;     // boxes per axis in the sampling grid
  int sample_edge = 16;     // samples, edge of a sampling box

  // Its declaration (spec(), from_params(), to_params() and validate() follow: DeclaredOptions).
  static const OptionsTable<NormaliseOptions>& table();
};

class Normalise final : public Attribute {
public:
  // Throws InvalidArgument for a null input or invalid options. Reads nothing yet.
  explicit Normalise(VolumePtr input, const NormaliseOptions& options = {});
  const NormaliseOptions& options() const { return options_; }

  // The divisor. For the percentile method, computed on first use (thread-safe); throws DataError
  // if the sample holds a non-finite value or if the percentile is 0 (pass a fixed scale then),
  // and whatever reading the input throws.
  double scale() const;
  // The boxes of the percentile's sample, in the order they are read.
  std::vector<Box> sample_boxes() const;

protected:
  void compute(const Box& box, std::span<float> out) const override;

private:
  double estimate_scale() const;

  NormaliseOptions options_;
  mutable std::once_flag scale_once_;
  mutable double scale_ = 0.0;
};

} // namespace geotandem::attributes
