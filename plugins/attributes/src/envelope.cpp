#include "geotandem/attributes/envelope.hpp"

#include <cmath>

#include "filters.hpp"
#include "mirror.hpp"

namespace geotandem::attributes {

const OptionsTable<EnvelopeOptions>& EnvelopeOptions::table() {
  static const OptionsTable<EnvelopeOptions> table{
      "envelope",
      "instantaneous amplitude |u + i H[u]|, Hilbert transform along the trace",
      1,
      {option(ParamSpec{.name = "half_length",
                        .type = ParamType::integer,
                        .help = "half-length of the Blackman-windowed FIR Hilbert transformer (2*half_length+1 taps, "
                                "and the halo along the trace); 32 keeps the gain within 4e-4 of 1 from 0.05 to 0.45 "
                                "cycles per sample",
                        .min_value = 2,
                        .max_value = 512,
                        .unit = "samples"},
              &EnvelopeOptions::half_length)}};
  return table;
}

Envelope::Envelope(VolumePtr input, const EnvelopeOptions& options)
    : Attribute("envelope", to_string(EnvelopeOptions::validated(options).to_params()), {std::move(input)},
                {0, 0, options.half_length}),
      options_(options), taps_(detail::hilbert_kernel(options.half_length).half) {}

void Envelope::compute(const Box& box, std::span<float> out) const {
  const detail::Kernel kernel{taps_, detail::Symmetry::odd};
  const detail::Array3 u = detail::read_mirrored(*inputs().front(), box, halo());
  const detail::Array3 h = detail::correlate(u, 2, kernel);
  const auto nk = static_cast<std::size_t>(box.size(2));
  const auto lines = static_cast<std::size_t>(box.size(0) * box.size(1));
  const auto nk_in = static_cast<std::size_t>(u.shape[2]);
  const auto r = static_cast<std::size_t>(options_.half_length);
  for (std::size_t line = 0; line < lines; ++line) {
    const float* ul = u.data.get() + line * nk_in + r;
    const float* hl = h.data.get() + line * nk;
    float* o = out.data() + line * nk;
    for (std::size_t k = 0; k < nk; ++k)
      o[k] = std::sqrt(ul[k] * ul[k] + hl[k] * hl[k]);
  }
}

} // namespace geotandem::attributes
