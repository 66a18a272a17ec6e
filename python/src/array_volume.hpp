#pragma once
// A numpy array (or np.memmap) as a geotandem volume: read(box) copies only the box out of the
// array's buffer, so an array mapped from a file larger than memory is read block by block and
// never whole. The buffer is borrowed: the caller keeps the array alive while the volume is used.

#include <string>

#include "geotandem/volume/volume.hpp"

namespace geotandem::python {

class ArrayVolume final : public volume::Volume {
public:
  // `samples`: C-contiguous float32 of geometry.shape. `release_pages`: the buffer is a read-only
  // shared file mapping (np.memmap mode "r"), whose pages are handed back to the page cache once a
  // box is copied (madvise MADV_DONTNEED), so that what was read does not stay in this process's
  // resident memory; never for memory the process owns (it would be lost).
  ArrayVolume(volume::Geometry geometry, const float* samples, bool release_pages, std::string source);

  const volume::Geometry& geometry() const override { return geometry_; }
  std::string format() const override { return release_pages_ ? "numpy memmap" : "numpy array"; }
  std::string source() const override { return source_; }

protected:
  void read_box(const volume::Box& box, std::span<float> out) const override;

private:
  volume::Geometry geometry_;
  const float* samples_;
  bool release_pages_;
  std::string source_;
};

} // namespace geotandem::python
