#include "array_volume.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "geotandem/core/error.hpp"

namespace geotandem::python {

ArrayVolume::ArrayVolume(volume::Geometry geometry, const float* samples, std::string source, const std::string& file,
                         std::uint64_t file_offset)
    : geometry_(std::move(geometry)), samples_(samples), source_(std::move(source)), file_(file),
      file_offset_(file_offset) {
  geometry_.validate();
  if (!file_.empty()) {
    fd_ = ::open(file_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) throw IoError(std::string("cannot open the memmap's file: ") + std::strerror(errno), {file_});
  }
}

ArrayVolume::~ArrayVolume() {
  if (fd_ >= 0) ::close(fd_);
}

void ArrayVolume::read_file(std::uint64_t index, std::size_t count, float* dst) const {
  auto* bytes = reinterpret_cast<char*>(dst);
  std::size_t left = count * sizeof(float);
  auto offset = static_cast<off_t>(file_offset_ + index * sizeof(float));
  while (left > 0) {
    const ssize_t got = ::pread(fd_, bytes, left, offset);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0)
      throw IoError(got < 0 ? std::string("cannot read the memmap's file: ") + std::strerror(errno)
                            : "the memmap's file ends before the array does (truncated?)",
                    {file_});
    bytes += got, offset += got, left -= static_cast<std::size_t>(got);
  }
}

void ArrayVolume::read_box(const volume::Box& box, std::span<float> out) const {
  const std::int64_t nj = geometry_.shape[1], nk = geometry_.shape[2];
  const std::int64_t dj = box.hi[1] - box.lo[1], dk = box.hi[2] - box.lo[2];
  float* dst = out.data();
  for (std::int64_t i = box.lo[0]; i < box.hi[0]; ++i) {
    const auto first = static_cast<std::uint64_t>((i * nj + box.lo[1]) * nk + box.lo[2]);
    if (fd_ >= 0 && dk == nk) { // whole traces: this inline's part of the box is one run of the file
      read_file(first, static_cast<std::size_t>(dj * nk), dst);
      dst += dj * nk;
      continue;
    }
    for (std::int64_t j = 0; j < dj; ++j) {
      const std::uint64_t at = first + static_cast<std::uint64_t>(j * nk);
      if (fd_ >= 0)
        read_file(at, static_cast<std::size_t>(dk), dst);
      else
        std::memcpy(dst, samples_ + at, static_cast<std::size_t>(dk) * sizeof(float));
      dst += dk;
    }
  }
}

} // namespace geotandem::python
