#pragma once
// Product of two volumes of the same shape, sample by sample ("chaos x normalised envelope" for
// chaotic and high-amplitude facies). No parameters, no halo of its own.

#include "geotandem/attributes/attribute.hpp"
#include "geotandem/attributes/params.hpp"

namespace geotandem::attributes {

struct ProductOptions : DeclaredOptions<ProductOptions> {
  // Its declaration (spec(), from_params(), to_params() and validate() follow: DeclaredOptions).
  static const OptionsTable<ProductOptions>& table();
};

class Product final : public Attribute {
public:
  // Throws InvalidArgument if an input is null or the two shapes differ.
  Product(VolumePtr first, VolumePtr second);

protected:
  void compute(const Box& box, std::span<float> out) const override;
};

} // namespace geotandem::attributes
