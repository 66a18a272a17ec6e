#include "geotandem/volume/box.hpp"

#include <algorithm>
#include <cstring>

namespace geotandem::volume {

bool Box::contains(const Box& other) const {
  for (int a = 0; a < 3; ++a)
    if (other.lo[a] < lo[a] || other.hi[a] > hi[a]) return false;
  return true;
}

bool Box::contains(const Index3& index) const {
  for (int a = 0; a < 3; ++a)
    if (index[a] < lo[a] || index[a] >= hi[a]) return false;
  return true;
}

Box Box::grown(const Index3& halo) const {
  Box b = *this;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] -= halo[a];
    b.hi[a] += halo[a];
  }
  return b;
}

Box Box::hull(const Box& other) const {
  Box b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = std::min(lo[a], other.lo[a]);
    b.hi[a] = std::max(hi[a], other.hi[a]);
  }
  return b;
}

Box Box::intersection(const Box& other) const {
  Box b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = std::max(lo[a], other.lo[a]);
    b.hi[a] = std::max(b.lo[a], std::min(hi[a], other.hi[a]));
  }
  return b;
}

std::string Box::to_string() const {
  return "[" + std::to_string(lo[0]) + ":" + std::to_string(hi[0]) + ", " + std::to_string(lo[1]) + ":" +
         std::to_string(hi[1]) + ", " + std::to_string(lo[2]) + ":" + std::to_string(hi[2]) + "]";
}

void copy_region(const float* src, const Box& src_box, float* dst, const Box& dst_box, const Box& region) {
  if (region.empty()) return;
  const auto run = static_cast<std::size_t>(region.size(2));
  for (std::int64_t i = region.lo[0]; i < region.hi[0]; ++i)
    for (std::int64_t j = region.lo[1]; j < region.hi[1]; ++j) {
      const Index3 start{i, j, region.lo[2]};
      std::memcpy(dst + dst_box.offset(start), src + src_box.offset(start), run * sizeof(float));
    }
}

} // namespace geotandem::volume
