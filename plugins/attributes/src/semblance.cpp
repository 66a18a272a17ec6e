#include "geotandem/attributes/semblance.hpp"

#include <algorithm>

#include "filters.hpp"
#include "mirror.hpp"

namespace geotandem::attributes {

const OptionsTable<SemblanceOptions>& SemblanceOptions::table() {
  static const OptionsTable<SemblanceOptions> table{
      "semblance",
      "Marfurt semblance of a square of traces in a window along the trace (1 = identical traces)",
      1,
      {option(odd_window("traces", "width of the square of traces centred on the output trace (3 gives 3 x 3 traces)",
                         3, 21, "traces"),
              &SemblanceOptions::traces),
       option(odd_window("window", "length of the centred window along the trace", 1, 1001),
              &SemblanceOptions::window)}};
  return table;
}

Semblance::Semblance(VolumePtr input, const SemblanceOptions& options)
    : Attribute("semblance", to_string(SemblanceOptions::validated(options).to_params()), {std::move(input)},
                {(options.traces - 1) / 2, (options.traces - 1) / 2, (options.window - 1) / 2}),
      options_(options) {}

void Semblance::compute(const Box& box, std::span<float> out) const {
  const detail::Kernel across = detail::box_kernel(static_cast<int>(halo()[0]));
  const detail::Kernel along = detail::box_kernel(static_cast<int>(halo()[2]));

  detail::Array3 f = detail::read_mirrored(*inputs().front(), box, halo());
  detail::Array3 energy(f.shape);
  {
    const float* src = f.data.get();
    float* dst = energy.data.get();
    for (std::size_t n = 0; n < f.count(); ++n)
      dst[n] = src[n] * src[n];
  }
  // Stack of the traces (sum over the square) and its energy, then both summed over the window.
  detail::Array3 stack = detail::correlate(detail::correlate(f, 0, across), 1, across);
  f.reset();
  for (float& v : stack.span())
    v = v * v;
  const detail::Array3 numerator = detail::correlate(stack, 2, along);
  stack.reset();
  const detail::Array3 denominator =
      detail::correlate(detail::correlate(detail::correlate(energy, 0, across), 1, across), 2, along);

  const auto traces = static_cast<float>(options_.traces * options_.traces);
  const float* num = numerator.data.get();
  const float* den = denominator.data.get();
  for (std::size_t n = 0; n < out.size(); ++n) {
    const float d = traces * den[n];
    // Cauchy-Schwarz bounds S by 1; rounding may step over it, so clamp.
    out[n] = d > 0.0f ? std::min(1.0f, num[n] / d) : 1.0f;
  }
}

} // namespace geotandem::attributes
