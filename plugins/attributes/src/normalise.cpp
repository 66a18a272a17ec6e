#include "geotandem/attributes/normalise.hpp"

#include <algorithm>
#include <cmath>

#include "geotandem/core/error.hpp"

namespace geotandem::attributes {

const char* to_string(ScaleMethod method) {
  return method == ScaleMethod::percentile ? "percentile" : "fixed";
}

const AttributeSpec& NormaliseOptions::spec() {
  static const AttributeSpec spec{
      "normalise",
      "the input divided by a robust scale (a percentile of |input| on a sample of the cube) or a fixed value",
      1,
      {{"method",
        ParamType::choice,
        std::string("percentile"),
        {},
        false,
        {"percentile", "fixed"},
        "",
        "percentile: divide by a percentile of |input| estimated on a deterministic sample; fixed: divide by "
        "'scale'"},
       {"percentile",
        ParamType::real,
        99.0,
        {0, 100, true},
        false,
        {},
        "percent",
        "percentile (nearest rank) of |input| used as the scale by method percentile"},
       {"scale",
        ParamType::real,
        1.0,
        {0, std::numeric_limits<double>::infinity(), true, true},
        false,
        {},
        "",
        "the divisor used by method fixed, in the input's units"},
       {"sample_boxes",
        ParamType::integer,
        std::int64_t{4},
        {1, 16},
        false,
        {},
        "",
        "boxes per axis in the regular grid sampled by method percentile"},
       {"sample_edge",
        ParamType::integer,
        std::int64_t{16},
        {1, 256},
        false,
        {},
        "samples",
        "edge of one sampling box (clipped to the cube)"}}};
  return spec;
}

NormaliseOptions NormaliseOptions::from_params(const ParamValues& params) {
  ParamValues p = resolve(spec(), params);
  NormaliseOptions options;
  options.method = get_choice(p, "method") == "fixed" ? ScaleMethod::fixed : ScaleMethod::percentile;
  options.percentile = get_real(p, "percentile");
  options.scale = get_real(p, "scale");
  options.sample_boxes = static_cast<int>(get_integer(p, "sample_boxes"));
  options.sample_edge = static_cast<int>(get_integer(p, "sample_edge"));
  return options;
}

ParamValues NormaliseOptions::to_params() const {
  return {{"method", std::string(to_string(method))},
          {"percentile", percentile},
          {"scale", scale},
          {"sample_boxes", std::int64_t{sample_boxes}},
          {"sample_edge", std::int64_t{sample_edge}}};
}

void NormaliseOptions::validate() const {
  if (method != ScaleMethod::percentile && method != ScaleMethod::fixed)
    throw InvalidArgument("attribute 'normalise': unknown method value " + std::to_string(static_cast<int>(method)));
  check_real(spec(), "percentile", percentile);
  check_real(spec(), "scale", scale);
  check_integer(spec(), "sample_boxes", sample_boxes);
  check_integer(spec(), "sample_edge", sample_edge);
}

namespace {
NormaliseOptions validated(const NormaliseOptions& options) {
  options.validate();
  return options;
}

// The parameters that matter for the chosen method, for source().
std::string describe(const NormaliseOptions& o) {
  ParamValues p = o.to_params();
  if (o.method == ScaleMethod::fixed) return "method=fixed, scale=" + to_string(p.at("scale"));
  p.erase("scale");
  return to_string(p);
}
} // namespace

Normalise::Normalise(VolumePtr input, const NormaliseOptions& options)
    : Attribute("normalise", describe(validated(options)), {std::move(input)}, {0, 0, 0}, Tiling::whole_box),
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
    throw DataError("the " + to_string(ParamValue{options_.percentile}) + "th percentile of |input| over " +
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
