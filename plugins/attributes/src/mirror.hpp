#pragma once
// Reading a box plus its halo, with the mirror rule at the cube's faces (see attribute.hpp).

#include <cstdint>

#include "array3.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::attributes::detail {

// The index that `index` reads on an axis of `size` samples under half-sample symmetric
// reflection, repeated with period 2*size: -1 -> 0, -2 -> 1, size -> size-1, size+1 -> size-2.
// Precondition: size > 0.
inline std::int64_t mirror_index(std::int64_t index, std::int64_t size) {
  const std::int64_t period = 2 * size;
  std::int64_t r = index % period;
  if (r < 0) r += period;
  return r < size ? r : period - 1 - r;
}

// The samples of `box` grown by `halo` on each side of each axis, in C order of the grown box.
// Reads from `input` only the part of the grown box inside the cube (one read() call); the rest is
// filled by mirror_index. Throws what input.read throws.
Array3 read_mirrored(const volume::Volume& input, const volume::Box& box, const volume::Index3& halo);

} // namespace geotandem::attributes::detail
