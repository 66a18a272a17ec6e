#include "geotandem/attributes/rms.hpp"

#include <cmath>

#include "filters.hpp"
#include "mirror.hpp"

namespace geotandem::attributes {

const OptionsTable<RmsOptions>& RmsOptions::table() {
  static const OptionsTable<RmsOptions> table{
      "rms",
      "root mean square amplitude in a sliding window along the trace",
      1,
      {option(odd_window("window", "length of the centred window along the trace, about one dominant period", 1, 1001),
              &RmsOptions::window)}};
  return table;
}

Rms::Rms(VolumePtr input, const RmsOptions& options)
    : Attribute("rms", to_string(RmsOptions::validated(options).to_params()), {std::move(input)},
                {0, 0, (options.window - 1) / 2}),
      options_(options) {}

void Rms::compute(const Box& box, std::span<float> out) const {
  detail::Array3 squares = detail::read_mirrored(*inputs().front(), box, halo());
  for (float& v : squares.span())
    v = v * v;
  const detail::Array3 sums = detail::correlate(squares, 2, detail::box_kernel(static_cast<int>(halo()[2])));
  const float inverse = 1.0f / static_cast<float>(options_.window);
  const float* s = sums.data.get();
  for (std::size_t n = 0; n < out.size(); ++n)
    out[n] = std::sqrt(s[n] * inverse);
}

} // namespace geotandem::attributes
