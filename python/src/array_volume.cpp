#include "array_volume.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>

namespace geotandem::python {

ArrayVolume::ArrayVolume(volume::Geometry geometry, const float* samples, bool release_pages, std::string source)
    : geometry_(std::move(geometry)), samples_(samples), release_pages_(release_pages), source_(std::move(source)) {
  geometry_.validate();
}

void ArrayVolume::read_box(const volume::Box& box, std::span<float> out) const {
  const std::int64_t nj = geometry_.shape[1], nk = geometry_.shape[2];
  const std::int64_t dk = box.hi[2] - box.lo[2];
  static const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
  float* dst = out.data();
  for (std::int64_t i = box.lo[0]; i < box.hi[0]; ++i) {
    const float* slab = samples_ + (i * nj + box.lo[1]) * nk + box.lo[2];
    for (std::int64_t j = box.lo[1]; j < box.hi[1]; ++j) {
      std::memcpy(dst, slab + (j - box.lo[1]) * nk, static_cast<std::size_t>(dk) * sizeof(float));
      dst += dk;
    }
    if (release_pages_) {
      // The pages this inline's part of the box spans, rounded outwards: other readers of those
      // pages fault them in again from the page cache, nothing is lost in a read-only mapping.
      const auto first = reinterpret_cast<std::uintptr_t>(slab) & ~(page - 1);
      const auto last = reinterpret_cast<std::uintptr_t>(slab + (box.hi[1] - 1 - box.lo[1]) * nk + dk);
      ::madvise(reinterpret_cast<void*>(first), last - first, MADV_DONTNEED);
    }
  }
}

} // namespace geotandem::python
