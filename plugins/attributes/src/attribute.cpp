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
  for (const VolumePtr& input : inputs_) {
    const Index3 h = input->source_halo(); // an attribute's total halo; 0 for stored data
    for (int a = 0; a < 3; ++a)
      below[a] = std::max(below[a], h[a]);
  }
  return {halo_[0] + below[0], halo_[1] + below[1], halo_[2] + below[2]};
}

// Tiles per axis for `n` samples: as few as keep each tile within 5/4 of kTile, so that a box a
// little larger than a tile (a block of 129 samples) is not cut into a full tile and a sliver that
// would pay the whole halo for one sample.
std::int64_t Attribute::tiles_along(std::int64_t n, int axis) {
  const std::int64_t most = kTile[axis] + kTile[axis] / 4;
  return std::max<std::int64_t>(1, (n + most - 1) / most);
}

void Attribute::read_box(const Box& box, std::span<float> out) const {
  Index3 count{};
  for (int a = 0; a < 3; ++a)
    count[a] = tiling_ == Tiling::whole_box ? 1 : tiles_along(box.size(a), a);
  if (count[0] * count[1] * count[2] == 1) {
    compute(box, out);
    return;
  }
  // Even split: tile t of m covers [lo + t n / m, lo + (t + 1) n / m) on each axis.
  auto edge = [&](int a, std::int64_t t) { return box.lo[a] + t * box.size(a) / count[a]; };
  std::vector<float> tile_samples;
  for (std::int64_t ti = 0; ti < count[0]; ++ti)
    for (std::int64_t tj = 0; tj < count[1]; ++tj)
      for (std::int64_t tk = 0; tk < count[2]; ++tk) {
        const Box tile{{edge(0, ti), edge(1, tj), edge(2, tk)}, {edge(0, ti + 1), edge(1, tj + 1), edge(2, tk + 1)}};
        tile_samples.resize(tile.count());
        compute(tile, tile_samples);
        volume::copy_region(tile_samples.data(), tile, out.data(), box, tile);
      }
}

} // namespace geotandem::attributes
