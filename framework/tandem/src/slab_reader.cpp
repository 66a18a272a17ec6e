#include "slab_reader.hpp"

#include <algorithm>
#include <cstring>

namespace geotandem::tandem::detail {

namespace {
// The slab storage of the last reader destroyed on this thread, for the next one.
thread_local std::vector<float> spare_slab;
} // namespace

SlabReader::SlabReader(const volume::Volume& volume, const volume::Box& samples, int axis, std::int64_t slab_samples)
    : volume_(volume), samples_(samples), axis_(axis) {
  values_.swap(spare_slab); // its old values stay until the first read replaces them
  const std::int64_t section =
      std::max<std::int64_t>(1, samples.count() / std::max<std::int64_t>(1, samples.size(axis)));
  // As many sections as the budget holds, but at least 8 halos' worth (a computed volume then pays
  // its halo at most 1.25 times per slab), as long as that stays within 4 budgets.
  const std::int64_t by_budget = slab_samples / section;
  const std::int64_t by_halo = std::min(8 * volume.source_halo()[axis], 4 * slab_samples / section);
  per_slab_ = std::clamp<std::int64_t>(std::max(by_budget, by_halo), 1, samples.size(axis));
}

void SlabReader::release_spare() {
  std::vector<float>().swap(spare_slab);
}

SlabReader::~SlabReader() {
  if (values_.capacity() > spare_slab.capacity()) values_.swap(spare_slab);
}

void SlabReader::read(std::int64_t section, std::span<float> out) {
  const int a = axis_;
  if (slab_.empty() || section < slab_.lo[a] || section >= slab_.hi[a]) {
    slab_ = samples_;
    slab_.lo[a] = section;
    slab_.hi[a] = std::min(section + per_slab_, samples_.hi[a]);
    values_.resize(static_cast<std::size_t>(slab_.count()));
    volume_.read(slab_, values_);
  }
  // The section in the slab's C order: the two other axes keep their order (u slower than v).
  const int u = a == 0 ? 1 : 0, v = a == 2 ? 1 : 2;
  const volume::Index3 shape = slab_.shape();
  const std::int64_t stride[3] = {shape[1] * shape[2], shape[2], 1};
  const std::int64_t nu = shape[u], nv = shape[v];
  const float* base = values_.data() + (section - slab_.lo[a]) * stride[a];
  float* o = out.data();
  if (stride[v] == 1) {
    for (std::int64_t iu = 0; iu < nu; ++iu, o += nv)
      std::memcpy(o, base + iu * stride[u], static_cast<std::size_t>(nv) * sizeof(float));
    return;
  }
  for (std::int64_t iu = 0; iu < nu; ++iu)
    for (std::int64_t iv = 0; iv < nv; ++iv)
      *o++ = base[iu * stride[u] + iv * stride[v]];
}

} // namespace geotandem::tandem::detail
