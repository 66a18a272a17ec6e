#include "geotandem/attributes/attribute.hpp"

#include <algorithm>
#include <vector>

#include "geotandem/core/error.hpp"

namespace geotandem::attributes {

Attribute::Attribute(std::string name, std::string parameters, std::vector<VolumePtr> inputs, Index3 halo,
                     Tiling tiling)
    : name_(std::move(name)), parameters_(std::move(parameters)), inputs_(std::move(inputs)), halo_(halo),
      tiling_(tiling) {
  if (inputs_.empty()) throw InvalidArgument("attribute '" + name_ + "' was given no input volume");
  for (std::size_t n = 0; n < inputs_.size(); ++n)
    if (!inputs_[n])
      throw InvalidArgument("attribute '" + name_ + "': input " + std::to_string(n + 1) + " is null", {},
                            "pass an opened volume or another attribute");
  const Index3& shape = inputs_.front()->geometry().shape;
  for (std::size_t n = 1; n < inputs_.size(); ++n)
    if (inputs_[n]->geometry().shape != shape)
      throw InvalidArgument("attribute '" + name_ + "': input " + std::to_string(n + 1) + " has shape " +
                                inputs_[n]->geometry().bounds().to_string() + " but input 1 has shape " +
                                inputs_.front()->geometry().bounds().to_string(),
                            {inputs_[n]->source()}, "combine volumes computed from the same cube");
}

std::string Attribute::source() const {
  std::string text = name_ + "(" + parameters_ + ") of ";
  for (std::size_t n = 0; n < inputs_.size(); ++n)
    text += (n ? " and " : "") + inputs_[n]->source();
  return text;
}

Index3 Attribute::total_halo() const {
  Index3 below{0, 0, 0};
  for (const VolumePtr& input : inputs_)
    if (const auto* attribute = dynamic_cast<const Attribute*>(input.get())) {
      Index3 h = attribute->total_halo();
      for (int a = 0; a < 3; ++a)
        below[a] = std::max(below[a], h[a]);
    }
  return {halo_[0] + below[0], halo_[1] + below[1], halo_[2] + below[2]};
}

void Attribute::read_box(const Box& box, std::span<float> out) const {
  bool fits = true;
  for (int a = 0; a < 3; ++a)
    fits = fits && box.size(a) <= kTile[a];
  if (fits || tiling_ == Tiling::whole_box) {
    compute(box, out);
    return;
  }
  std::vector<float> tile_samples;
  for (std::int64_t i = box.lo[0]; i < box.hi[0]; i += kTile[0])
    for (std::int64_t j = box.lo[1]; j < box.hi[1]; j += kTile[1])
      for (std::int64_t k = box.lo[2]; k < box.hi[2]; k += kTile[2]) {
        const Box tile = Box{{i, j, k}, {i + kTile[0], j + kTile[1], k + kTile[2]}}.intersection(box);
        tile_samples.resize(tile.count());
        compute(tile, tile_samples);
        volume::copy_region(tile_samples.data(), tile, out.data(), box, tile);
      }
}

} // namespace geotandem::attributes
