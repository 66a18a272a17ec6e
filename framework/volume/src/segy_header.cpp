#include "segy_header.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <vector>

#include "geotandem/core/error.hpp"

namespace geotandem::volume::detail::segy {

double ibm_to_double(std::uint32_t bits) {
  // sign (1 bit), exponent (7 bits, base 16, excess 64), fraction (24 bits, no hidden bit).
  const std::uint32_t fraction = bits & 0x00FFFFFFu;
  if (fraction == 0) return 0.0;
  const int exponent = static_cast<int>((bits >> 24) & 0x7Fu) - 64;
  const double magnitude = std::ldexp(static_cast<double>(fraction), 4 * exponent - 24);
  return (bits & 0x80000000u) ? -magnitude : magnitude;
}

namespace {

std::uint32_t unsigned_at(const TraceHeader& h, int byte, int width) {
  std::uint32_t v = 0;
  const unsigned char* p = h.bytes.data() + (byte - 1);
  for (int n = 0; n < width; ++n) {
    const unsigned char b = h.little_endian ? p[width - 1 - n] : p[n];
    v = (v << 8) | b;
  }
  return v;
}

// The standard's 2-byte fields among those geotandem reads (segyio's table has the rest).
bool two_bytes(int position) {
  switch (position) {
  case 29: // trace identification code
  case 31:
  case 33:
  case 35:
  case 69:  // elevation scalar
  case 71:  // coordinate scalar
  case 89:  // coordinate units
  case 109: // delay recording time
  case 115: // samples in this trace
  case 117: // sample interval
  case 215: // time scalar
    return true;
  default: return false;
  }
}

} // namespace

double value(const TraceHeader& h, const HeaderField& f) {
  switch (f.type) {
  case HeaderType::int16: return static_cast<std::int16_t>(unsigned_at(h, f.byte, 2));
  case HeaderType::int32: return static_cast<std::int32_t>(unsigned_at(h, f.byte, 4));
  case HeaderType::ieee: {
    const std::uint32_t bits = unsigned_at(h, f.byte, 4);
    float v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  case HeaderType::ibm: return ibm_to_double(unsigned_at(h, f.byte, 4));
  }
  return 0.0;
}

int field(const TraceHeader& h, int position) {
  if (two_bytes(position)) return static_cast<std::int16_t>(unsigned_at(h, position, 2));
  return static_cast<std::int32_t>(unsigned_at(h, position, 4));
}

struct HeaderFile::Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

HeaderFile::HeaderFile(const std::string& path, const Layout& layout)
    : fd_(std::make_shared<Fd>()), path_(path), layout_(layout) {
  fd_->fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_->fd < 0) throw IoError(std::string("cannot open the SEG-Y file: ") + std::strerror(errno), {path});
}

namespace {

// pread until `size` bytes are read; false at the end of the file.
bool read_at(int fd, unsigned char* out, std::size_t size, long long offset) {
  while (size > 0) {
    const ssize_t got = ::pread(fd, out, size, static_cast<off_t>(offset));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;
    out += got;
    size -= static_cast<std::size_t>(got);
    offset += got;
  }
  return true;
}

} // namespace

TraceHeader HeaderFile::read(int trace) const {
  TraceHeader h;
  h.little_endian = layout_.little_endian;
  if (trace < 0 || trace >= layout_.traces ||
      !read_at(fd_->fd, h.bytes.data(), h.bytes.size(), layout_.header_offset(trace)))
    throw IoError("cannot read the header of trace " + std::to_string(trace) + " (byte " +
                      std::to_string(layout_.header_offset(trace)) + " of the file)",
                  {path_});
  return h;
}

void HeaderFile::scan(const std::function<void(int, const TraceHeader&)>& visit, Progress& progress) const {
  const long long stride = layout_.stride();
  const int per_chunk = static_cast<int>(std::max<long long>(1, (8ll << 20) / stride));
  std::vector<unsigned char> chunk;
  TraceHeader h;
  h.little_endian = layout_.little_endian;
  progress.begin("reading trace headers", static_cast<std::uint64_t>(layout_.traces), "traces");
  struct StopUnlessEnded {
    Progress& report;
    bool ended = false;
    ~StopUnlessEnded() {
      if (!ended) report.stop();
    }
  } guard{progress};
  for (int first = 0; first < layout_.traces; first += per_chunk) {
    const int count = std::min(per_chunk, layout_.traces - first);
    // The last trace's samples are not needed: stop at its header's end.
    const std::size_t size =
        static_cast<std::size_t>(count - 1) * static_cast<std::size_t>(stride) + SEGY_TRACE_HEADER_SIZE;
    chunk.resize(size);
    if (!read_at(fd_->fd, chunk.data(), size, layout_.header_offset(first)))
      throw IoError("cannot read the headers of traces " + std::to_string(first) + " to " +
                        std::to_string(first + count - 1),
                    {path_});
    for (int n = 0; n < count; ++n) {
      std::memcpy(h.bytes.data(), chunk.data() + static_cast<std::size_t>(n) * static_cast<std::size_t>(stride),
                  h.bytes.size());
      visit(first + n, h);
    }
    progress.update(static_cast<std::uint64_t>(first) + static_cast<std::uint64_t>(count));
  }
  progress.end();
  guard.ended = true;
}

} // namespace geotandem::volume::detail::segy
