#pragma once
// Product of two volumes of the same shape, sample by sample ("chaos x normalised envelope" for
// chaotic and high-amplitude facies). No parameters, no halo of its own.

#include "geotandem/attributes/attribute.hpp"
#include "geotandem/attributes/params.hpp"

namespace geotandem::attributes {

struct ProductOptions {
  static const AttributeSpec& spec();
  // Throws InvalidArgument for any parameter (the product takes none).
  static ProductOptions from_params(const ParamValues& params);
};

class Product final : public Attribute {
public:
  // Throws InvalidArgument if an input is null or the two shapes differ.
  Product(VolumePtr first, VolumePtr second);

protected:
  void compute(const Box& box, std::span<float> out) const override;
};

} // namespace geotandem::attributes
