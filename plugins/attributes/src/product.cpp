#include "geotandem/attributes/product.hpp"

#include "array3.hpp"

namespace geotandem::attributes {

const OptionsTable<ProductOptions>& ProductOptions::table() {
  static const OptionsTable<ProductOptions> table{
      "product", "sample-by-sample product of two volumes of the same shape", 2, {}};
  return table;
}

Product::Product(VolumePtr first, VolumePtr second)
    : Attribute("product", "", {std::move(first), std::move(second)}, {0, 0, 0}) {}

void Product::compute(const Box& box, std::span<float> out) const {
  inputs()[0]->read(box, out);
  detail::Array3 second(box.shape()); // box-sized: reused storage (array3.hpp)
  inputs()[1]->read(box, second.span());
  const float* factor = second.data.get();
  for (std::size_t n = 0; n < out.size(); ++n)
    out[n] *= factor[n];
}

} // namespace geotandem::attributes
