#include "mirror.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace geotandem::attributes::detail {

Array3 read_mirrored(const volume::Volume& input, const volume::Box& box, const volume::Index3& halo) {
  const volume::Box bounds = input.geometry().bounds();
  const volume::Box grown = box.grown(halo);
  Array3 out(grown.shape());
  if (bounds.contains(grown)) {
    input.read(grown, out.span());
    return out;
  }

  // Every mirrored index of the grown box falls inside its part within the cube: an index below 0
  // only occurs when that part starts at 0 and its image is at most halo-1-lo < hi+halo, or it
  // reaches the cube's end (and symmetrically at the far face). The check below guards it.
  const volume::Box inside = grown.intersection(bounds);
  Array3 source(inside.shape());
  input.read(inside, source.span());
  std::vector<std::int64_t> map[3];
  for (int a = 0; a < 3; ++a) {
    map[a].reserve(static_cast<std::size_t>(grown.size(a)));
    for (std::int64_t m = grown.lo[a]; m < grown.hi[a]; ++m) {
      const std::int64_t local = mirror_index(m, bounds.hi[a]) - inside.lo[a];
      if (local < 0 || local >= inside.size(a))
        throw std::logic_error("mirror image of index " + std::to_string(m) + " leaves box " + inside.to_string());
      map[a].push_back(local);
    }
  }

  const std::size_t nk = static_cast<std::size_t>(grown.size(2));
  const std::int64_t in_nj = inside.size(1), in_nk = inside.size(2);
  // Along the trace the map is the identity shift when the grown box stays inside on that axis.
  const bool k_inside = grown.lo[2] >= 0 && grown.hi[2] <= bounds.hi[2];
  float* dst = out.data.get();
  for (std::int64_t mi : map[0])
    for (std::int64_t mj : map[1]) {
      const float* row = source.data.get() + (mi * in_nj + mj) * in_nk;
      if (k_inside) {
        std::memcpy(dst, row + map[2].front(), nk * sizeof(float));
      } else {
        for (std::size_t k = 0; k < nk; ++k)
          dst[k] = row[map[2][k]];
      }
      dst += nk;
    }
  return out;
}

} // namespace geotandem::attributes::detail
