#pragma once
// Semblance (Marfurt et al. 1998), without dip steering: for the square of M = traces x traces
// traces centred on the output trace and a centred window of `window` samples,
//   S = sum_k (sum_i f_ik)^2 / (M sum_k sum_i f_ik^2),
// i over the traces, k over the window. S is in [0, 1]: 1 where the traces are identical, about
// 1/M for uncorrelated noise. Where every sample of the window is zero, S is 1 (nothing varies).
// Halo: (traces - 1) / 2 across, (window - 1) / 2 along the trace; mirrored beyond the cube.

#include "geotandem/attributes/attribute.hpp"
#include "geotandem/attributes/params.hpp"

namespace geotandem::attributes {

struct SemblanceOptions : DeclaredOptions<SemblanceOptions> {
  int traces = 3; // width of the square of traces, odd
  int window = 9; // samples along the trace, odd

  // Its declaration (spec(), from_params(), to_params() and validate() follow: DeclaredOptions).
  static const OptionsTable<SemblanceOptions>& table();
};

class Semblance final : public Attribute {
public:
  // Throws InvalidArgument for a null input or invalid options.
  explicit Semblance(VolumePtr input, const SemblanceOptions& options = {});
  const SemblanceOptions& options() const { return options_; }

protected:
  void compute(const Box& box, std::span<float> out) const override;

private:
  SemblanceOptions options_;
};

} // namespace geotandem::attributes
