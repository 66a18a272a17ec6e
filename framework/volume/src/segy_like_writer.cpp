// write_segy_like (io.hpp): a cube written into a trace-for-trace copy of a SEG-Y file, keeping
// every header the file has (textual, binary, extended textual, trace headers and their
// extensions), in the file's trace order and byte order; only the samples are the cube's, as IEEE
// floats. This is how a label cube goes back to an interpretation package beside its seismic: the
// same inline/crossline and CDP X/Y at the same bytes, whatever they are.

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "formats.hpp"
#include "geotandem/core/error.hpp"
#include "segy_file.hpp"
#include "segy_grid.hpp"
#include "segy_grid_hint.hpp"
#include "segy_header.hpp"
#include "segy_layout.hpp"

namespace geotandem::volume::detail {
namespace {

using segy::Grid;
using segy::Layout;

// Reads exactly `size` bytes at `offset`; throws IoError naming `what` otherwise.
void read_exactly(int fd, char* out, std::size_t size, long long offset, const std::string& what,
                  const std::string& path) {
  while (size > 0) {
    const ssize_t got = ::pread(fd, out, size, static_cast<off_t>(offset));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0)
      throw IoError("cannot read " + what + (got < 0 ? std::string(": ") + std::strerror(errno) : ": end of file"),
                    {path});
    out += got;
    size -= static_cast<std::size_t>(got);
    offset += got;
  }
}

void write_exactly(int fd, const char* bytes, std::size_t size, long long offset, const std::string& path) {
  while (size > 0) {
    const ssize_t put = ::pwrite(fd, bytes, size, static_cast<off_t>(offset));
    if (put < 0 && errno == EINTR) continue;
    if (put < 0) throw IoError(std::string("write failed: ") + std::strerror(errno), {path}, "check the free space");
    bytes += put;
    size -= static_cast<std::size_t>(put);
    offset += put;
  }
}

// The printable ASCII characters a card may hold, in EBCDIC (code page 037); others become spaces.
unsigned char to_ebcdic(char c) {
  const auto u = static_cast<unsigned char>(std::toupper(static_cast<unsigned char>(c)));
  if (u >= 'A' && u <= 'I') return static_cast<unsigned char>(0xC1 + (u - 'A'));
  if (u >= 'J' && u <= 'R') return static_cast<unsigned char>(0xD1 + (u - 'J'));
  if (u >= 'S' && u <= 'Z') return static_cast<unsigned char>(0xE2 + (u - 'S'));
  if (u >= '0' && u <= '9') return static_cast<unsigned char>(0xF0 + (u - '0'));
  switch (u) {
  case '.': return 0x4B;
  case '(': return 0x4D;
  case '+': return 0x4E;
  case ')': return 0x5D;
  case ';': return 0x5E;
  case '-': return 0x60;
  case '/': return 0x61;
  case ',': return 0x6B;
  case '_': return 0x6D;
  case ':': return 0x7A;
  case '=': return 0x7E;
  case '\'': return 0x7D;
  default: return 0x40; // space
  }
}

// Puts `note` on a card of the 3200-byte textual header, in its own encoding (EBCDIC, or ASCII
// when the file's header is ASCII): the last blank card before card 39 (rev 1 and 2 keep their
// revision and "END TEXTUAL HEADER" cards at 39 and 40), or card 38 when none is blank. The card
// keeps its "Cnn" prefix; the note is upper-cased and cut to 76 characters.
void put_note(char* text, const std::string& note) {
  if (note.empty()) return;
  std::size_t ascii = 0, ebcdic = 0;
  for (std::size_t n = 0; n < SEGY_TEXT_HEADER_SIZE; ++n) {
    ascii += text[n] == ' ';
    ebcdic += static_cast<unsigned char>(text[n]) == 0x40;
  }
  const bool is_ebcdic = ebcdic >= ascii;
  const auto blank = [&](int card) {
    const char* c = text + static_cast<std::ptrdiff_t>(card) * 80;
    for (int n = 4; n < 80; ++n)
      if (is_ebcdic ? static_cast<unsigned char>(c[n]) != 0x40 : (c[n] != ' ' && c[n] != '\0')) return false;
    return true;
  };
  int card = 37; // card 38, 0-based
  for (int c = 37; c >= 1; --c)
    if (blank(c)) {
      card = c;
      break;
    }
  std::string line = note.substr(0, 76);
  line.resize(76, ' ');
  char* c = text + static_cast<std::ptrdiff_t>(card) * 80 + 4;
  for (std::size_t n = 0; n < line.size(); ++n)
    c[n] = is_ebcdic ? static_cast<char>(to_ebcdic(line[n]))
                     : static_cast<char>(std::toupper(static_cast<unsigned char>(line[n])));
}

// The two-byte big- or little-endian field at 1-based file byte `byte` of the binary header
// (which starts at file byte 3201).
void set_binary_int16(char* bin, int byte, int value, bool little_endian) {
  const auto v = static_cast<std::uint16_t>(value);
  char* p = bin + (byte - 3201);
  p[little_endian ? 0 : 1] = static_cast<char>(v & 0xFF);
  p[little_endian ? 1 : 0] = static_cast<char>(v >> 8);
}

// IEEE float samples in the file's byte order.
void encode_samples(const float* in, std::size_t count, char* out, bool little_endian) {
  for (std::size_t n = 0; n < count; ++n) {
    std::uint32_t bits;
    std::memcpy(&bits, in + n, 4);
    for (int b = 0; b < 4; ++b)
      out[4 * n + static_cast<std::size_t>(b)] = static_cast<char>(bits >> (little_endian ? 8 * b : 8 * (3 - b)));
  }
}

} // namespace

void write_segy_like(const Volume& volume, const std::string& like, const OpenOptions& options, const std::string& path,
                     const WriteOptions& write, Progress& progress, const CancelToken& cancel) {
  segy::Handle file(segy_open(like.c_str(), "rb"));
  if (!file)
    throw IoError(std::string("cannot open the SEG-Y file: ") + std::strerror(errno), {like}, "check its permissions");
  const Layout layout = segy::read_layout(file.get(), like);
  file.reset();
  check_segy_options(options.segy, like);
  const segy::HeaderFile headers(like, layout);
  // The grid as open_volume(like, options) finds it (missing bins read as missing: they have no
  // trace to write).
  std::optional<Grid> hinted;
  if (!options.reopen_hint.empty())
    hinted = segy::grid_from_hint(options.reopen_hint, segy::file_stamp(like), options.segy, layout.traces);
  const Grid grid = hinted ? std::move(*hinted) : segy::find_grid(headers, layout, options.segy, true, like, nullptr);

  const Geometry& g = volume.geometry();
  if (g.shape != Index3{grid.ni, grid.nj, layout.samples})
    throw InvalidArgument("the cube is " + Box::of_shape(g.shape).to_string() +
                              ", but the SEG-Y file it is written "
                              "like holds " +
                              std::to_string(grid.ni) + " x " + std::to_string(grid.nj) + " traces of " +
                              std::to_string(layout.samples) + " samples",
                          {like}, "write it like the file it was computed from");

  // Every header of the file up to its first trace: textual, binary, extended textual headers.
  const int in_fd = ::open(like.c_str(), O_RDONLY | O_CLOEXEC);
  if (in_fd < 0) throw IoError(std::string("cannot open the SEG-Y file: ") + std::strerror(errno), {like});
  struct CloseIn {
    int fd;
    ~CloseIn() { ::close(fd); }
  } close_in{in_fd};
  std::vector<char> head(static_cast<std::size_t>(layout.trace0));
  read_exactly(in_fd, head.data(), head.size(), 0, "the file headers", like);
  put_note(head.data(), write.note);
  set_binary_int16(head.data() + SEGY_TEXT_HEADER_SIZE, 3225, SEGY_IEEE_FLOAT_4_BYTE, layout.little_endian);

  const std::size_t header_bytes =
      static_cast<std::size_t>(SEGY_TRACE_HEADER_SIZE) * (1u + static_cast<unsigned>(layout.header_extensions));
  const auto ns = static_cast<std::size_t>(layout.samples);
  const std::size_t out_stride = header_bytes + 4 * ns;
  const auto out_offset = [&](int trace) {
    return static_cast<long long>(layout.trace0) + static_cast<long long>(out_stride) * trace;
  };

  int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0)
    throw IoError(std::string("cannot create the SEG-Y file: ") + std::strerror(errno), {path},
                  "check that the directory exists and is writable, and that nothing is there");
  try {
    write_exactly(fd, head.data(), head.size(), 0, path);
    // Traces in slabs of whole inlines (reads of a lazy cube are fastest in inline order), each
    // written at its own place in the file: an unsorted file's order is kept as it is.
    const std::int64_t ni = g.shape[0], nj = g.shape[1];
    const std::int64_t per_slab =
        std::max<std::int64_t>(1, (std::int64_t{1} << 22) / std::max<std::int64_t>(1, nj * g.shape[2]));
    std::vector<float> slab;
    std::vector<char> trace(out_stride);
    std::vector<bool> written(static_cast<std::size_t>(layout.traces), false);
    progress.begin("writing SEG-Y " + path + " like " + like, static_cast<std::uint64_t>(ni), "inlines");
    for (std::int64_t i0 = 0; i0 < ni; i0 += per_slab) {
      cancel.throw_if_cancelled();
      const std::int64_t i1 = std::min(ni, i0 + per_slab);
      const Box box{{i0, 0, 0}, {i1, nj, g.shape[2]}};
      slab.resize(box.count());
      volume.read(box, slab);
      for (std::int64_t i = i0; i < i1; ++i)
        for (std::int64_t j = 0; j < nj; ++j) {
          const int t = grid.trace_of(i, j);
          if (t < 0) continue; // a bin of an irregular survey without a trace
          read_exactly(in_fd, trace.data(), header_bytes, layout.header_offset(t),
                       "the header of trace " + std::to_string(t), like);
          encode_samples(slab.data() + box.offset({i, j, 0}), ns, trace.data() + header_bytes, layout.little_endian);
          write_exactly(fd, trace.data(), trace.size(), out_offset(t), path);
          written[static_cast<std::size_t>(t)] = true;
        }
      progress.update(static_cast<std::uint64_t>(i1));
    }
    // Traces of the file outside the grid (placeholders left out of an irregular survey): their
    // headers as they are, zero samples.
    for (int t = 0; t < layout.traces; ++t) {
      if (written[static_cast<std::size_t>(t)]) continue;
      read_exactly(in_fd, trace.data(), header_bytes, layout.header_offset(t),
                   "the header of trace " + std::to_string(t), like);
      std::fill(trace.begin() + static_cast<std::ptrdiff_t>(header_bytes), trace.end(), '\0');
      write_exactly(fd, trace.data(), trace.size(), out_offset(t), path);
    }
    progress.end();
    const int closed = ::close(fd);
    fd = -1;
    if (closed != 0)
      throw IoError(std::string("write failed on close: ") + std::strerror(errno), {path}, "check the free space");
  } catch (...) {
    if (fd >= 0) ::close(fd);
    std::error_code ec;
    std::filesystem::remove(path, ec);
    throw;
  }
}

} // namespace geotandem::volume::detail
