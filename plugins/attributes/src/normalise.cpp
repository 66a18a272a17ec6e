#include "geotandem/attributes/normalise.hpp"

#include <algorithm>
#include <cmath>

#include "geotandem/core/error.hpp"

namespace geotandem::attributes {

const char* to_string(ScaleMethod method) {
  return method == ScaleMethod::percentile ? "percentile" : "fixed";
}

const OptionsTable<NormaliseOptions>& NormaliseOptions::table() {
  static const OptionsTable<NormaliseOptions> table{
      "normalise",
      "the input divided by a robust scale (a percentile of |input| on a sample of the cube) or a fixed value",
      1,
      {choice(ParamSpec{.name = "method",
                        .type = ParamType::choice,
                        .help = "percentile: divide by a percentile of |input| estimated on a deterministic sample; "
                                "fixed: divide by 'scale'",
                        .choices = {"percentile", "fixed"}},
              &NormaliseOptions::method),
       option(ParamSpec{.name = "percentile",
                        .type = ParamType::real,
                        .help = "percentile (nearest rank) of |input| used as the scale by method percentile",
                        .min_value = 0,
                        .max_value = 100,
                        .min_open = true,
                        .unit = "percent"},
              &NormaliseOptions::percentile),
       option(ParamSpec{.name = "scale",
                        .type = ParamType::real,
                        .help = "the divisor used by method fixed, in the input's units",
                        .min_value = 0,
                        .min_open = true,
                        .single_precision = true},
              &NormaliseOptions::scale),
       option(ParamSpec{.name = "sample_boxes",
                        .type = ParamType::integer,
                        .help = "boxes per axis in the regular grid sampled by method percentile",
                        .min_value = 1,
                        .max_value = 16},
              &NormaliseOptions::sample_boxes),
       option(ParamSpec{.name = "sample_edge",
                        .type = ParamType::integer,
                        .help = "edge of one sampling box (clipped to the cube)",
                        .min_value = 1,
                        .max_value = 256,
                        .unit = "samples"},
              &NormaliseOptions::sample_edge)}};
  return table;
}

namespace {

// The parameters that matter for the chosen method, for source().
std::string describe(const NormaliseOptions& o) {
  ParamValues p = o.to_params();
  if (o.method == ScaleMethod::fixed) return "method=fixed, scale=" + p.at("scale").text;
  p.erase("scale");
  return to_string(p);
}
} // namespace

Normalise::Normalise(VolumePtr input, const NormaliseOptions& options)
    : Attribute("normalise", describe(NormaliseOptions::validated(options)), {std::move(input)}, {0, 0, 0},
                Tiling::whole_box),
      options_(options) {}

std::vector<Box> Normalise::sample_boxes() const {
  const Index3& shape = geometry().shape;
  // Per axis: n boxes of edge e, no more than fit side by side, first at 0 and last at the far face.
  std::vector<std::int64_t> starts[3];
  Index3 edge{};
  for (int a = 0; a < 3; ++a) {
    edge[a] = std::min<std::int64_t>(options_.sample_edge, shape[a]);
    const std::int64_t n = std::clamp<std::int64_t>(shape[a] / edge[a], 1, options_.sample_boxes);
    for (std::int64_t b = 0; b < n; ++b)
      starts[a].push_back(n == 1 ? (shape[a] - edge[a]) / 2 : b * (shape[a] - edge[a]) / (n - 1));
  }
  std::vector<Box> boxes;
  for (std::int64_t i : starts[0])
    for (std::int64_t j : starts[1])
      for (std::int64_t k : starts[2])
        boxes.push_back(Box{{i, j, k}, {i + edge[0], j + edge[1], k + edge[2]}});
  return boxes;
}

double Normalise::estimate_scale() const {
  std::vector<float> magnitudes;
  for (const Box& box : sample_boxes()) {
    std::vector<float> values = inputs().front()->read(box);
    for (float v : values) {
      if (!std::isfinite(v))
        throw DataError("non-finite value in the sample used to estimate the normalisation scale",
                        {inputs().front()->source(), {}, {}, "box " + box.to_string(), {}},
                        "open the input with a NaN fill policy, or use method fixed");
      magnitudes.push_back(std::abs(v));
    }
  }
  // Nearest rank: the smallest value with at least percentile % of the sample at or below it.
  const auto count = static_cast<double>(magnitudes.size());
  auto rank = static_cast<std::size_t>(std::ceil(options_.percentile / 100.0 * count));
  rank = std::clamp<std::size_t>(rank, 1, magnitudes.size()) - 1;
  std::nth_element(magnitudes.begin(), magnitudes.begin() + static_cast<std::ptrdiff_t>(rank), magnitudes.end());
  const double scale = magnitudes[rank];
  if (!(scale > 0.0))
    throw DataError("the " + number_text(options_.percentile) + "th percentile of |input| over " +
                        std::to_string(magnitudes.size()) + " sampled values is 0, so it cannot be a scale",
                    {inputs().front()->source()}, "use method fixed with a scale, or a higher percentile");
  return scale;
}

double Normalise::scale() const {
  if (options_.method == ScaleMethod::fixed) return options_.scale;
  std::call_once(scale_once_, [this] { scale_ = estimate_scale(); });
  return scale_;
}

void Normalise::compute(const Box& box, std::span<float> out) const {
  const auto divisor = static_cast<float>(scale());
  inputs().front()->read(box, out);
  for (float& v : out)
    v = v / divisor;
}

} // namespace geotandem::attributes
