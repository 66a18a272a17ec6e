#pragma once
// A numpy array (or np.memmap) as a geotandem volume: read(box) copies only the box, so an array
// mapped from a file larger than memory is read block by block and never whole. The buffer is
// borrowed: the caller keeps the array alive while the volume is used.

#include <cstdint>
#include <string>

#include "geotandem/volume/volume.hpp"

namespace geotandem::python {

class ArrayVolume final : public volume::Volume {
public:
  // `samples`: C-contiguous float32 of geometry.shape, read with memcpy. `file` (not empty): the
  // file a read-only memmap maps, with the samples from byte `file_offset`: its boxes are read
  // from the file with pread instead. The bytes are the same, but the mapping is never faulted in:
  // pages of a file mapping count in the process's resident memory until the kernel reclaims them
  // (handing them back with madvise after each box is not enough: a fault maps whole large folios
  // around it), so a 1 GiB memmap read through its mapping ended with most of it resident.
  ArrayVolume(volume::Geometry geometry, const float* samples, std::string source, const std::string& file = {},
              std::uint64_t file_offset = 0);
  ~ArrayVolume() override;
  ArrayVolume(const ArrayVolume&) = delete;
  ArrayVolume& operator=(const ArrayVolume&) = delete;

  const volume::Geometry& geometry() const override { return geometry_; }
  std::string format() const override { return fd_ >= 0 ? "numpy memmap" : "numpy array"; }
  std::string source() const override { return source_; }

protected:
  void read_box(const volume::Box& box, std::span<float> out) const override;

private:
  void read_file(std::uint64_t index, std::size_t count, float* dst) const;

  volume::Geometry geometry_;
  const float* samples_;
  std::string source_;
  std::string file_;
  std::uint64_t file_offset_ = 0;
  int fd_ = -1;
};

} // namespace geotandem::python
