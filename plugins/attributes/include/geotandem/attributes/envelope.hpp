#pragma once
// Envelope (instantaneous amplitude) |u + i H[u]|, with H the Hilbert transform along each trace
// only. H is a windowed FIR transformer (ideal taps 2/(pi n) for odd n, Blackman taper) of
// 2 * half_length + 1 taps, so a box needs half_length samples of halo along the trace; beyond the
// trace's ends the trace is mirrored (attribute.hpp). With the default half_length 32 the
// transformer's gain is within 4e-4 of 1 from 0.05 to 0.45 cycles per sample (12.5 to 112 Hz at
// 4 ms), so the envelope of a pure cosine in that band is constant to 4e-4 of its amplitude. Near
// 0 and near Nyquist the gain falls off and the envelope ripples. The first and last half_length
// samples of a trace see the mirror image and are approximate.

#include "geotandem/attributes/attribute.hpp"
#include "geotandem/attributes/params.hpp"

namespace geotandem::attributes {

struct EnvelopeOptions : DeclaredOptions<EnvelopeOptions> {
  int half_length = 32; // samples

  // Its declaration (spec(), from_params(), to_params() and validate() follow: DeclaredOptions).
  static const OptionsTable<EnvelopeOptions>& table();
};

class Envelope final : public Attribute {
public:
  // Throws InvalidArgument for a null input or invalid options.
  explicit Envelope(VolumePtr input, const EnvelopeOptions& options = {});
  const EnvelopeOptions& options() const { return options_; }

protected:
  void compute(const Box& box, std::span<float> out) const override;

private:
  EnvelopeOptions options_;
  std::vector<float> taps_; // Hilbert taps w(0..half_length)
};

} // namespace geotandem::attributes
