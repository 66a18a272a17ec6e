#pragma once
// Index-space boxes. Axis 0 is inline (i), axis 1 crossline (j), axis 2 sample (k). A box is the
// half-open range [lo, hi) on each axis. Samples of a box are stored in C order: sample fastest,
// then crossline, then inline (the order of a SEG-Y trace and of a C-order [il, xl, sample] array).

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace geotandem::volume {

using Index3 = std::array<std::int64_t, 3>;

struct Box {
  Index3 lo{0, 0, 0};
  Index3 hi{0, 0, 0};

  static Box of_shape(const Index3& shape) { return Box{{0, 0, 0}, shape}; }

  std::int64_t size(int axis) const { return hi[axis] - lo[axis]; }
  Index3 shape() const { return {size(0), size(1), size(2)}; }
  bool empty() const { return size(0) <= 0 || size(1) <= 0 || size(2) <= 0; }
  // Number of samples; 0 when empty.
  std::size_t count() const {
    return empty() ? 0
                   : static_cast<std::size_t>(size(0)) * static_cast<std::size_t>(size(1)) *
                         static_cast<std::size_t>(size(2));
  }
  bool contains(const Box& other) const;
  bool contains(const Index3& index) const;
  // Offset of a global index inside this box's C-order buffer (index must be inside).
  std::size_t offset(const Index3& index) const {
    return (static_cast<std::size_t>(index[0] - lo[0]) * static_cast<std::size_t>(size(1)) +
            static_cast<std::size_t>(index[1] - lo[1])) *
               static_cast<std::size_t>(size(2)) +
           static_cast<std::size_t>(index[2] - lo[2]);
  }
  // The box grown by `halo` samples on each side of each axis (may leave the cube: clip it).
  Box grown(const Index3& halo) const;
  Box intersection(const Box& other) const;
  // The smallest box holding both (non-empty) boxes.
  Box hull(const Box& other) const;
  // Whether two non-empty boxes share a sample (intersection() is not empty), without building it.
  bool overlaps(const Box& other) const {
    for (int a = 0; a < 3; ++a)
      if (!(lo[a] < other.hi[a] && other.lo[a] < hi[a])) return false;
    return true;
  }
  bool operator==(const Box&) const = default;

  // "[i0:i1, j0:j1, k0:k1]", the form used in every error message.
  std::string to_string() const;
};

// Copies the samples of `region` from `src` (laid out as `src_box`) into `dst` (laid out as
// `dst_box`). `region` must lie inside both boxes.
void copy_region(const float* src, const Box& src_box, float* dst, const Box& dst_box, const Box& region);

} // namespace geotandem::volume
