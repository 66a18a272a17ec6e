#pragma once
// A dense 3D float array in C order (axis 2 fastest), the working storage of the filters. Its
// samples are left uninitialised: every producer writes all of them.

#include <cstddef>
#include <memory>
#include <span>

#include "geotandem/volume/box.hpp"

namespace geotandem::attributes::detail {

struct Array3 {
  volume::Index3 shape{0, 0, 0};
  std::unique_ptr<float[]> data;

  Array3() = default;
  explicit Array3(const volume::Index3& extent)
      : shape(extent), data(std::make_unique_for_overwrite<float[]>(count())) {}

  std::size_t count() const {
    return static_cast<std::size_t>(shape[0]) * static_cast<std::size_t>(shape[1]) * static_cast<std::size_t>(shape[2]);
  }
  std::span<float> span() { return {data.get(), count()}; }
  std::span<const float> span() const { return {data.get(), count()}; }
  void reset() {
    data.reset();
    shape = {0, 0, 0};
  }
};

} // namespace geotandem::attributes::detail
