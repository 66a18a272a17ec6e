#pragma once
// RMS amplitude sqrt(mean(u^2)) over a centred sliding window along each trace. A box needs
// (window - 1) / 2 samples of halo along the trace; beyond the trace's ends the trace is mirrored
// (attribute.hpp). The window should span about one dominant period (9 to 11 samples at 4 ms for
// 25 Hz).

#include "geotandem/attributes/attribute.hpp"
#include "geotandem/attributes/params.hpp"

namespace geotandem::attributes {

struct RmsOptions : DeclaredOptions<RmsOptions> {
  int window = 9; // samples, odd

  // Its declaration (spec(), from_params(), to_params() and validate() follow: DeclaredOptions).
  static const OptionsTable<RmsOptions>& table();
};

class Rms final : public Attribute {
public:
  // Throws InvalidArgument for a null input or invalid options.
  explicit Rms(VolumePtr input, const RmsOptions& options = {});
  const RmsOptions& options() const { return options_; }

protected:
  void compute(const Box& box, std::span<float> out) const override;

private:
  RmsOptions options_;
};

} // namespace geotandem::attributes
