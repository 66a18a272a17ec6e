#pragma once
// Cross-sections of a block served from slabs: one Volume::read fetches several consecutive
// cross-sections along the extraction axis at once, and the extractor takes them one by one.
//
// Why: a computed volume (an attribute chain) pays its halo on every read. Read one cross-section
// at a time, a chaos attribute with a halo of 12 recomputes every sample about 25 times; read in
// slabs of T sections, the halo costs (T + 2 halo) / T instead. Sections are asked for in increasing
// order, so every section is read exactly once and the slab is never read again.
//
// The slab's thickness comes from the budget (slab_samples) and from the volume's halo along the
// axis (Volume::source_halo, the total halo of an attribute chain): at least 8 halos of sections,
// so that the halo costs at most (8 + 2) / 8 of the slab, unless that takes more than 4 budgets.
//
// Memory: one slab of at most max(4 slab_samples, one cross-section) samples, plus the copy of the
// section handed out. A reader takes over the slab storage its thread's last reader left (kept
// while no reader is alive: one slab a thread), so that the next block reuses pages already
// faulted in instead of having the kernel zero and map a fresh slab's worth for every block (two
// thirds of the page faults of an analytic 512^3 extraction before).

#include <cstdint>
#include <span>
#include <vector>

#include "geotandem/volume/volume.hpp"

namespace geotandem::tandem::detail {

class SlabReader {
public:
  // `samples`: the block's samples; `axis`: the axis the sections are stacked along;
  // `slab_samples`: the budget of one slab (at least one section is always read).
  SlabReader(const volume::Volume& volume, const volume::Box& samples, int axis, std::int64_t slab_samples);
  ~SlabReader();
  SlabReader(const SlabReader&) = delete;
  SlabReader& operator=(const SlabReader&) = delete;

  // Writes cross-section `section` (a global index along the axis, inside the block) into `out`, in
  // the C order of the one-sample-thick box. Sections are expected in increasing order; asking
  // for one before the current slab rereads (correct, only slower).
  void read(std::int64_t section, std::span<float> out);

  std::int64_t sections_per_slab() const { return per_slab_; }
  // Frees the storage kept on the calling thread for its next reader.
  static void release_spare();

private:
  const volume::Volume& volume_;
  volume::Box samples_;
  int axis_;
  std::int64_t per_slab_;
  volume::Box slab_{};
  std::vector<float> values_;
};

} // namespace geotandem::tandem::detail
