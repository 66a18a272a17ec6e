#pragma once
// A dense 3D float array in C order (axis 2 fastest), the working storage of the filters. Its
// samples are left uninitialised: every producer writes all of them.
//
// Storage: an array of at least kReusedFloats samples takes its storage from the few that arrays
// freed earlier on the same thread left (array3.cpp). An attribute read allocates the same few
// box-sized arrays, block after block and slab after slab; those are megabytes, above geotandem's
// malloc mmap threshold (apps/geotandem/main.cpp), and each new mapping faulted its pages in again.

#include <cstddef>
#include <memory>
#include <span>

#include "geotandem/volume/box.hpp"

namespace geotandem::attributes::detail {

// Arrays of fewer samples than this come from malloc as usual (1 MiB of floats).
inline constexpr std::size_t kReusedFloats = std::size_t{1} << 18;

// Gives `data` (room for `capacity` floats) back to the calling thread's spares, or frees it.
struct ArrayStorageRelease {
  std::size_t capacity = 0;
  void operator()(float* data) const noexcept;
};
using ArrayStorage = std::unique_ptr<float[], ArrayStorageRelease>;

// Room for `count` floats, uninitialised: a spare of the calling thread's when one is large enough
// and at most twice as large, a new allocation otherwise.
ArrayStorage take_array_storage(std::size_t count);

// The bytes the calling thread keeps in spares, and freeing them.
std::size_t spare_array_bytes();
void release_spare_arrays();

struct Array3 {
  volume::Index3 shape{0, 0, 0};
  ArrayStorage data;

  Array3() = default;
  explicit Array3(const volume::Index3& extent) : shape(extent), data(take_array_storage(count())) {}

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
