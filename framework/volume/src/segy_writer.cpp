// SEG-Y rev 1 writer: IEEE floats (format 5), inline-sorted, one inline slab in memory at a time.
// segyio writes the file headers and encodes every trace header and sample.
// Every number SEG-Y stores as an integer (line numbers, interval, delay, coordinates) is checked
// to be representable before the first byte is written, so that a file is either right or absent.

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "formats.hpp"
#include "geotandem/core/error.hpp"
#include "segy_file.hpp"

namespace geotandem::volume::detail {
namespace {

// The integers a geometry becomes in the headers.
struct Encoding {
  int il0 = 0, il_step = 1, xl0 = 0, xl_step = 1;
  int interval = 0;               // microseconds (time) or millimetres (depth)
  int delay = 0;                  // z0 in units of 1/|delay_scalar|
  int delay_scalar = 1;           // trace header byte 215: 1 or -10^n
  int coordinate_scalar = 1;      // trace header byte 71: 1, 10, ... or -10, -100 (divide)
  double coordinate_factor = 1.0; // world metres times this = stored integer
};

bool near_integer(double value, double tolerance = 1e-6) {
  return std::isfinite(value) && std::abs(value - std::round(value)) <= tolerance * std::max(1.0, std::abs(value));
}

int to_int32(double value) {
  return static_cast<int>(std::llround(value));
}

bool fits_int32(double value) {
  return std::abs(value) < 2147483647.0;
}

int line_number(double value, const char* what, const std::string& path) {
  if (!near_integer(value) || !fits_int32(value))
    throw InvalidArgument(std::string(what) + " is " + std::to_string(value) +
                              "; SEG-Y stores line numbers as 32-bit integers",
                          {path}, "give the cube integer line numbers, or write it as .nc, .zarr or .raw");
  return to_int32(value);
}

Encoding encode(const Geometry& g, const std::string& path) {
  Encoding e;
  e.il0 = line_number(g.inline0, "the first inline number", path);
  e.il_step = line_number(g.inline_step, "the inline step", path);
  e.xl0 = line_number(g.crossline0, "the first crossline number", path);
  e.xl_step = line_number(g.crossline_step, "the crossline step", path);
  line_number(g.inline0 + g.inline_step * static_cast<double>(g.shape[0] - 1), "the last inline number", path);
  line_number(g.crossline0 + g.crossline_step * static_cast<double>(g.shape[1] - 1), "the last crossline number", path);
  if (e.il_step == 0 || e.xl_step == 0)
    throw InvalidArgument("a line step is 0: every trace would carry the same line number", {path});

  if (g.shape[2] > 65535)
    throw InvalidArgument("SEG-Y rev 1 holds at most 65535 samples per trace; the cube has " +
                              std::to_string(g.shape[2]),
                          {path}, "write it as .nc, .zarr or .raw, or cut the sample axis into pieces");
  const double interval = g.dz * 1000.0;
  if (!near_integer(interval) || std::llround(interval) < 1 || std::llround(interval) > 65535)
    throw InvalidArgument("the sample interval " + std::to_string(g.dz) + " " + to_string(g.z_unit) +
                              " is not a whole number of 1/1000 " + to_string(g.z_unit) + " between 1 and 65535",
                          {path}, "SEG-Y stores the interval as a 16-bit integer; resample, or write .nc or .zarr");
  e.interval = to_int32(interval);

  // z0 goes to the delay recording time, a 16-bit integer, with the rev 1 time scalar (byte 215)
  // when z0 is not a whole number.
  e.delay_scalar = 0;
  for (int digits = 0, factor = 1; digits <= 4; ++digits, factor *= 10) {
    const double scaled = g.z0 * factor;
    if (near_integer(scaled, 1e-9) && std::abs(scaled) <= 32767.0) {
      e.delay = to_int32(scaled);
      e.delay_scalar = digits == 0 ? 1 : -factor;
      break;
    }
  }
  if (e.delay_scalar == 0)
    throw InvalidArgument("the first sample's z0 = " + std::to_string(g.z0) + " " + to_string(g.z_unit) +
                              " does not fit the 16-bit delay field with up to 4 decimals",
                          {path}, "write .nc, .zarr or .raw, or crop the cube so that z0 is representable");

  // Coordinates: the finest of centimetres, decimetres, metres, ... that fits 32 bits at every
  // corner (the affine is linear, so the corners hold the extremes).
  double extreme = 0.0;
  for (double i : {0.0, static_cast<double>(g.shape[0] - 1)})
    for (double j : {0.0, static_cast<double>(g.shape[1] - 1)})
      for (double c : g.affine.apply(i, j))
        extreme = std::max(extreme, std::abs(c));
  static constexpr std::array<std::pair<int, double>, 6> scalars{
      {{-100, 100.0}, {-10, 10.0}, {1, 1.0}, {10, 0.1}, {100, 0.01}, {1000, 0.001}}};
  for (auto [scalar, factor] : scalars)
    if (fits_int32(extreme * factor)) {
      e.coordinate_scalar = scalar;
      e.coordinate_factor = factor;
      return e;
    }
  throw InvalidArgument("world coordinates up to " + std::to_string(extreme) + " m do not fit SEG-Y's 32-bit fields",
                        {path}, "check the survey affine");
}

std::string number(double value) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.10g", value);
  return text.data();
}

// 40 cards of 80 characters; segyio turns them into EBCDIC.
std::string textual_header(const Geometry& g, const Encoding& e, const std::string& note) {
  const auto& s = g.shape;
  const bool depth = g.z_unit == SampleUnit::metres;
  std::vector<std::string> cards = {
      std::string(segy::kMark) + " SEG-Y REV 1, IEEE FLOAT (FORMAT 5), INLINE-SORTED",
      "SHAPE: " + std::to_string(s[0]) + " INLINES X " + std::to_string(s[1]) + " CROSSLINES X " +
          std::to_string(s[2]) + " SAMPLES",
      "INLINES " + std::to_string(e.il0) + " STEP " + std::to_string(e.il_step) + " (BYTE 189), CROSSLINES " +
          std::to_string(e.xl0) + " STEP " + std::to_string(e.xl_step) + " (BYTE 193)",
      depth
          ? std::string(segy::kDepthMark) + " M, Z0 " + number(g.z0) + " DZ " + number(g.dz) + " (INTERVAL FIELD IN MM)"
          : "SAMPLE AXIS: TIME MS, Z0 " + number(g.z0) + " DZ " + number(g.dz) + " (INTERVAL FIELD IN US)",
      "Z0 AT BYTE 109 SCALED BY BYTE 215 = " + std::to_string(e.delay_scalar),
      "CDP X, Y AT BYTES 181, 185 SCALED BY BYTE 71 = " + std::to_string(e.coordinate_scalar) + ", METRES",
      "X = " + number(g.affine.x0) + " + " + number(g.affine.xi) + " * I + " + number(g.affine.xj) + " * J",
      "Y = " + number(g.affine.y0) + " + " + number(g.affine.yi) + " * I + " + number(g.affine.yj) + " * J",
      "I, J: INLINE AND CROSSLINE INDICES FROM 0",
  };
  if (!note.empty()) { // what the cube holds (a label cube says so), upper-case as the other cards
    std::string card = note.substr(0, 75);
    for (char& c : card)
      c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    cards.push_back(card);
  }
  std::string text;
  for (std::size_t n = 0; n < 40; ++n) {
    std::array<char, 8> prefix{};
    std::snprintf(prefix.data(), prefix.size(), "C%02zu ", n + 1);
    std::string card = prefix.data();
    if (n < cards.size()) card += cards[n];
    if (n == 39) card += "END TEXTUAL HEADER";
    card.resize(80, ' ');
    text += card;
  }
  return text;
}

void check(int status, const std::string& what, const std::string& path) {
  if (status != SEGY_OK) throw IoError("cannot write the " + what + ": " + segy::status_text(status), {path});
}

std::array<char, SEGY_BINARY_HEADER_SIZE> binary_header(const Geometry& g, const Encoding& e) {
  std::array<char, SEGY_BINARY_HEADER_SIZE> bin{};
  const auto samples = static_cast<int>(g.shape[2]);
  const std::pair<int, int> fields[] = {
      {SEGY_BIN_TRACES, static_cast<int>(std::min<std::int64_t>(g.shape[1], 32767))},
      {SEGY_BIN_INTERVAL, e.interval},
      {SEGY_BIN_INTERVAL_ORIG, e.interval},
      {SEGY_BIN_SAMPLES, samples},
      {SEGY_BIN_SAMPLES_ORIG, samples},
      {SEGY_BIN_FORMAT, SEGY_IEEE_FLOAT_4_BYTE},
      {SEGY_BIN_ENSEMBLE_FOLD, 1},
      {SEGY_BIN_SORTING_CODE, 4},       // horizontally stacked
      {SEGY_BIN_MEASUREMENT_SYSTEM, 1}, // metres
      {SEGY_BIN_SEGY_REVISION, 0x0100}, // rev 1.0
      {SEGY_BIN_TRACE_FLAG, 1},         // every trace has the same length
      {SEGY_BIN_EXT_HEADERS, 0},
  };
  for (auto [position, value] : fields)
    segy_set_bfield(bin.data(), position, value);
  return bin;
}

void fill_trace_header(std::array<char, SEGY_TRACE_HEADER_SIZE>& h, const Geometry& g, const Encoding& e,
                       std::int64_t i, std::int64_t j, int trace) {
  h.fill(0);
  const auto xy = g.affine.apply(static_cast<double>(i), static_cast<double>(j));
  const int x = to_int32(xy[0] * e.coordinate_factor), y = to_int32(xy[1] * e.coordinate_factor);
  const std::pair<int, int> fields[] = {
      {SEGY_TR_SEQ_LINE, trace + 1},
      {SEGY_TR_SEQ_FILE, trace + 1},
      {SEGY_TR_ENSEMBLE, trace + 1},
      {SEGY_TR_NUM_IN_ENSEMBLE, 1},
      {SEGY_TR_TRACE_ID, 1}, // seismic data
      {SEGY_TR_ELEV_SCALAR, 1},
      {SEGY_TR_SOURCE_GROUP_SCALAR, e.coordinate_scalar},
      {SEGY_TR_SOURCE_X, x},
      {SEGY_TR_SOURCE_Y, y},
      {SEGY_TR_COORD_UNITS, 1}, // length (metres, binary header byte 3255)
      {SEGY_TR_DELAY_REC_TIME, e.delay},
      {SEGY_TR_SAMPLE_COUNT, static_cast<int>(g.shape[2])},
      {SEGY_TR_SAMPLE_INTER, e.interval},
      {SEGY_TR_CDP_X, x},
      {SEGY_TR_CDP_Y, y},
      {SEGY_TR_INLINE, e.il0 + static_cast<int>(i) * e.il_step},
      {SEGY_TR_CROSSLINE, e.xl0 + static_cast<int>(j) * e.xl_step},
      {SEGY_TR_SCALAR_TRACE_HEADER, e.delay_scalar},
  };
  for (auto [position, value] : fields)
    segy_set_field(h.data(), position, value);
}

void write_all(int fd, const char* bytes, std::size_t count, const std::string& path) {
  while (count > 0) {
    ssize_t put = ::write(fd, bytes, count);
    if (put < 0 && errno == EINTR) continue;
    if (put < 0) throw IoError(std::string("write failed: ") + std::strerror(errno), {path}, "check the free space");
    bytes += put;
    count -= static_cast<std::size_t>(put);
  }
}

// Traces go out one inline at a time, headers and samples interleaved in one buffer and one
// write: through segyio's per-trace calls every trace cost two seeks and two small writes.
// The bytes are still made by segyio (segy_set_field, segy_from_native).
void write_traces(int fd, const Volume& volume, const Encoding& e, const std::string& path, Progress& progress,
                  const CancelToken& cancel) {
  const Geometry& g = volume.geometry();
  const std::int64_t ni = g.shape[0], nj = g.shape[1], nk = g.shape[2];
  if (ni * nj > std::numeric_limits<int>::max())
    throw InvalidArgument("the cube has " + std::to_string(ni * nj) + " traces, more than SEG-Y readers can address",
                          {path}, "write it as .nc or .zarr");
  const auto sample_bytes = static_cast<std::size_t>(nk) * sizeof(float);
  const std::size_t trace_bytes = SEGY_TRACE_HEADER_SIZE + sample_bytes;
  std::vector<float> slab(static_cast<std::size_t>(nj * nk));
  std::vector<char> out(static_cast<std::size_t>(nj) * trace_bytes);
  std::array<char, SEGY_TRACE_HEADER_SIZE> header{};
  progress.begin("writing SEG-Y " + path, static_cast<std::uint64_t>(ni), "inlines");
  for (std::int64_t i = 0; i < ni; ++i) {
    cancel.throw_if_cancelled();
    volume.read(Box{{i, 0, 0}, {i + 1, nj, nk}}, slab);
    segy_from_native(SEGY_IEEE_FLOAT_4_BYTE, static_cast<long long>(slab.size()), slab.data());
    for (std::int64_t j = 0; j < nj; ++j) {
      fill_trace_header(header, g, e, i, j, static_cast<int>(i * nj + j));
      char* trace = out.data() + static_cast<std::size_t>(j) * trace_bytes;
      std::memcpy(trace, header.data(), header.size());
      std::memcpy(trace + SEGY_TRACE_HEADER_SIZE, slab.data() + j * nk, sample_bytes);
    }
    write_all(fd, out.data(), out.size(), path);
    progress.update(static_cast<std::uint64_t>(i + 1));
  }
  progress.end();
}

} // namespace

void write_segy(const Volume& volume, const std::string& path, const WriteOptions& options, Progress& progress,
                const CancelToken& cancel) {
  const Geometry& g = volume.geometry();
  g.validate();
  const Encoding e = encode(g, path);

  segy::Handle file(segy_open(path.c_str(), "w+b"));
  if (!file)
    throw IoError(std::string("cannot create the SEG-Y file: ") + std::strerror(errno), {path},
                  "check that the directory exists and is writable");
  int fd = -1;
  try {
    const std::string text = textual_header(g, e, options.note);
    check(segy_write_textheader(file.get(), 0, text.c_str()), "textual header", path);
    const auto bin = binary_header(g, e);
    check(segy_write_binheader(file.get(), bin.data()), "binary header", path);
    check(segy::close(file), "file headers (flush on close)", path);

    fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    if (fd < 0) throw IoError(std::string("cannot reopen the SEG-Y file: ") + std::strerror(errno), {path});
    write_traces(fd, volume, e, path, progress, cancel);
    const int closed = ::close(fd);
    fd = -1;
    if (closed != 0)
      throw IoError(std::string("write failed on close: ") + std::strerror(errno), {path}, "check the free space");
  } catch (...) {
    // A partial file would look like a truncated cube: leave nothing behind.
    file.reset();
    if (fd >= 0) ::close(fd);
    std::error_code ec;
    std::filesystem::remove(path, ec);
    throw;
  }
}

} // namespace geotandem::volume::detail
