#include "geotandem/attributes/product.hpp"

namespace geotandem::attributes {

const AttributeSpec& ProductOptions::spec() {
  static const AttributeSpec spec{"product", "sample-by-sample product of two volumes of the same shape", 2, {}};
  return spec;
}

ProductOptions ProductOptions::from_params(const ParamValues& params) {
  resolve(spec(), params);
  return {};
}

Product::Product(VolumePtr first, VolumePtr second)
    : Attribute("product", "", {std::move(first), std::move(second)}, {0, 0, 0}) {}

void Product::compute(const Box& box, std::span<float> out) const {
  inputs()[0]->read(box, out);
  const std::vector<float> second = inputs()[1]->read(box);
  for (std::size_t n = 0; n < out.size(); ++n)
    out[n] *= second[n];
}

} // namespace geotandem::attributes
