// The binary header of a SEG-Y file: byte order, sample format, trace sizes and count.

#include "segy_layout.hpp"

#include <array>
#include <filesystem>

#include "geotandem/core/error.hpp"

namespace geotandem::volume::detail::segy {
namespace {

using TraceHeader = std::array<char, SEGY_TRACE_HEADER_SIZE>;
using BinaryHeader = std::array<char, SEGY_BINARY_HEADER_SIZE>;

constexpr int kFormatByte = 3225;

bool supported(int format) {
  return format == SEGY_IBM_FLOAT_4_BYTE || format == SEGY_SIGNED_INTEGER_4_BYTE ||
         format == SEGY_SIGNED_SHORT_2_BYTE || format == SEGY_IEEE_FLOAT_4_BYTE || format == SEGY_SIGNED_CHAR_1_BYTE;
}

// The codes SEG-Y rev 2 defines (13 and 14 are unassigned); any of them is a plausible value.
bool defined_code(int code) {
  return (code >= 1 && code <= 12) || code == 15 || code == 16;
}

const char* const defined_codes = "SEG-Y defines 1 to 12, 15 and 16";
const char* const readable_codes = "geotandem reads IBM float (1), 32-bit integer (2), 16-bit integer (3), IEEE "
                                   "float (5) and 8-bit integer (8) samples in either byte order";

// Unsigned 16-bit field of the binary header at 1-based file byte `byte`, in either byte order.
int field16(const BinaryHeader& raw, int byte, bool little_endian) {
  const auto a = static_cast<unsigned char>(raw[static_cast<std::size_t>(byte - 3201)]);
  const auto b = static_cast<unsigned char>(raw[static_cast<std::size_t>(byte - 3200)]);
  return little_endian ? (b << 8 | a) : (a << 8 | b);
}

// Bytes per sample of a defined format code.
int bytes_per_sample(int format) {
  switch (format) {
  case 3:
  case 11: return 2;
  case 6:
  case 9:
  case 12: return 8;
  case 7:
  case 15: return 3;
  case 8:
  case 16: return 1;
  default: return 4;
  }
}

// Whether the rest of the binary header reads sensibly little-endian, for a format code that is
// defined only that way. A big-endian code of 256 (a damaged header) reads 1 little-endian, so the
// code alone cannot tell: in a file written little-endian, the sample interval is a positive 16-bit
// number, or the samples per trace make whole traces of the file's size, or both counts are 0 (they
// are in the trace headers). Otherwise the code is taken as written big-endian and refused.
bool reads_little_endian(const BinaryHeader& raw, int format, const std::string& path) {
  const int interval = field16(raw, 3217, true), samples = field16(raw, 3221, true);
  if (interval > 0 && interval < 0x8000) return true;
  if (interval == 0 && samples == 0) return true;
  const int extended = field16(raw, 3505, true);
  if (samples == 0 || extended >= 0x8000) return false;
  std::error_code ec;
  const auto size = static_cast<long long>(std::filesystem::file_size(path, ec));
  const long long trace0 = 3600LL + 3200LL * extended;
  const long long per_trace = SEGY_TRACE_HEADER_SIZE + static_cast<long long>(samples) * bytes_per_sample(format);
  return !ec && size >= trace0 + per_trace && (size - trace0) % per_trace == 0;
}

// The sample format code as stored, read in both byte orders; decides the file's byte order.
// segyio reads headers big-endian until told otherwise. A code that is no SEG-Y format in either
// order is named as the standard's big-endian reading gives it.
bool detect_little_endian(const BinaryHeader& raw, const std::string& path) {
  const int big = field16(raw, kFormatByte, false), little = field16(raw, kFormatByte, true);
  if (defined_code(big)) return false;
  if (defined_code(little) && reads_little_endian(raw, little, path)) return true;
  std::string also;
  if (little != big && defined_code(little))
    also = "; read little-endian it would be " + std::to_string(little) +
           ", but the sample interval and trace sizes do not read little-endian either";
  throw FormatError("sample format code " + std::to_string(big) +
                        " (binary header bytes 3225-3226) is not a SEG-Y "
                        "format code (" +
                        defined_codes + ")" + also,
                    {path}, std::string("the binary header is damaged, or the file is not SEG-Y; ") + readable_codes);
}

std::int32_t field32(const BinaryHeader& raw, int byte, bool little_endian) {
  const auto hi = static_cast<std::uint32_t>(field16(raw, little_endian ? byte + 2 : byte, little_endian));
  const auto lo = static_cast<std::uint32_t>(field16(raw, little_endian ? byte : byte + 2, little_endian));
  return static_cast<std::int32_t>(hi << 16 | lo);
}

int field(const TraceHeader& header, int position) {
  std::int32_t value = 0;
  segy_get_field(header.data(), position, &value);
  return value;
}

} // namespace

int Layout::sample_size() const {
  return format == SEGY_SIGNED_SHORT_2_BYTE ? 2 : format == SEGY_SIGNED_CHAR_1_BYTE ? 1 : 4;
}

int Layout::segyio_format() const {
  return format | static_cast<int>(little_endian ? SEGY_LSB : SEGY_MSB);
}

std::string Layout::revision_text() const {
  return std::to_string(revision_major) + "." + std::to_string(revision_minor);
}

const char* sample_format_name(int format) {
  switch (format) {
  case 1: return "IBM float";
  case 2: return "32-bit integer";
  case 3: return "16-bit integer";
  case 4: return "fixed point with gain";
  case 5: return "IEEE float";
  case 6: return "64-bit IEEE float";
  case 7: return "24-bit integer";
  case 8: return "8-bit integer";
  case 9: return "64-bit integer";
  case 10: return "unsigned 32-bit integer";
  case 11: return "unsigned 16-bit integer";
  case 12: return "unsigned 64-bit integer";
  case 15: return "unsigned 24-bit integer";
  case 16: return "unsigned 8-bit integer";
  default: return "unknown";
  }
}

Layout read_layout(segy_file* file, const std::string& path) {
  BinaryHeader bin{};
  if (int status = segy_binheader(file, bin.data()); status != SEGY_OK)
    throw FormatError(
        "cannot read the 400-byte binary header after the 3200-byte textual header: " + status_text(status), {path});
  const BinaryHeader raw = bin; // as the file holds it: segyio swaps a little-endian header field by field
  Layout layout;
  layout.little_endian = detect_little_endian(bin, path);
  // Rev 2 gives the revision as two bytes (major, minor); rev 1 wrote it as the 16-bit 0x0100, which a
  // little-endian writer stores as 00 01.
  layout.revision_major = static_cast<unsigned char>(raw[300]);
  layout.revision_minor = static_cast<unsigned char>(raw[301]);
  if (layout.little_endian && layout.revision_major == 0 && layout.revision_minor != 0)
    std::swap(layout.revision_major, layout.revision_minor);
  if (layout.little_endian) {
    // From here on segyio swaps every header field and sample it hands back to big-endian.
    segy_set_format(file, static_cast<int>(SEGY_IEEE_FLOAT_4_BYTE) | static_cast<int>(SEGY_LSB));
    if (int status = segy_binheader(file, bin.data()); status != SEGY_OK)
      throw FormatError("cannot read the binary header again: " + status_text(status), {path});
  }
  layout.format = segy_format(bin.data());
  if (!supported(layout.format))
    throw FormatError("sample format code " + std::to_string(layout.format) + " (" + sample_format_name(layout.format) +
                          ", binary header byte 3225) is not supported",
                      {path}, std::string(readable_codes) + "; convert the file to one of them");
  // Tells segyio the sample size for sub-trace reads, and the byte order.
  segy_set_format(file, layout.segyio_format());
  std::int32_t extended = 0;
  segy_get_bfield(bin.data(), SEGY_BIN_EXT_HEADERS, &extended);
  if (extended < 0)
    throw FormatError("a variable number of extended textual headers (binary header byte 3505 = " +
                          std::to_string(extended) + ") is not supported",
                      {path}, "rewrite the file with a fixed number of extended headers");
  std::int32_t measurement = 0;
  segy_get_bfield(bin.data(), SEGY_BIN_MEASUREMENT_SYSTEM, &measurement);
  layout.measurement_system = measurement;
  layout.trace0 = segy_trace0(bin.data());
  layout.extended_textual = extended;
  if (layout.revision_major >= 2) {
    const std::int32_t extensions = field32(raw, 3507, layout.little_endian);
    if (extensions < 0 || extensions > 1000)
      throw FormatError("the number of trace header extensions (binary header bytes 3507-3510) is " +
                            std::to_string(extensions),
                        {path}, "SEG-Y rev 2 allows 0 or more 240-byte extensions per trace; the header is damaged");
    layout.header_extensions = extensions;
  }

  // Samples per trace and the interval are unsigned 16-bit in SEG-Y rev 1; segyio 1.8 reads them
  // signed, hence the masks. A zero in the binary header falls back to the first trace header.
  int& samples = layout.samples;
  int& interval = layout.interval;
  samples = segy_samples(bin.data()) & 0xFFFF;
  std::int32_t value = 0;
  segy_get_bfield(bin.data(), SEGY_BIN_INTERVAL, &value);
  interval = value & 0xFFFF;
  if (samples == 0 || interval == 0) {
    TraceHeader first{};
    if (segy_traceheader(file, 0, first.data(), layout.trace0, 0) != SEGY_OK)
      throw FormatError("the file ends before its first trace header (byte " + std::to_string(layout.trace0) + ")",
                        {path});
    if (samples == 0) samples = field(first, SEGY_TR_SAMPLE_COUNT) & 0xFFFF;
    if (interval == 0) interval = field(first, SEGY_TR_SAMPLE_INTER) & 0xFFFF;
  }
  // Intervals above 32767 are a negative number written as signed 16 bits (no survey
  // samples that slowly): refused, never read as 61.536 ms for -4000.
  if (interval >= 0x8000)
    throw FormatError("the sample interval is negative (" + std::to_string(interval - 0x10000) +
                          "; binary header bytes 3217-3218, or trace header bytes 117-118)",
                      {path}, "set a positive sample interval in microseconds");
  if (samples == 0)
    throw FormatError("no samples per trace: binary header byte 3221 and trace header byte 115 are both 0", {path});
  layout.trace_bytes = segy_trsize(layout.format, samples);

  std::error_code ec;
  const auto size = static_cast<long long>(std::filesystem::file_size(path, ec));
  const long long per_trace = layout.stride();
  if (size < layout.trace0 + per_trace)
    throw FormatError("the file has " + std::to_string(size) + " bytes, less than its headers (" +
                          std::to_string(layout.trace0) + " bytes) and one trace (" + std::to_string(per_trace) +
                          " bytes)",
                      {path}, "the file is truncated or not SEG-Y");
  // The headers' extensions count in each trace's stride (segyio knows none).
  int status = segy_traces(file, &layout.traces, layout.trace0, layout.segyio_trace_bytes());
  if (status == SEGY_TRACE_SIZE_MISMATCH || (size - layout.trace0) % per_trace != 0) {
    long long whole = (size - layout.trace0) / per_trace;
    throw FormatError(
        "truncated or inconsistent SEG-Y: the file has " + std::to_string(size) + " bytes, but headers of " +
            std::to_string(layout.trace0) + " bytes plus whole traces of " + std::to_string(per_trace) + " bytes (" +
            std::to_string(samples) + " samples of " + sample_format_name(layout.format) + ") make " +
            std::to_string(layout.trace0 + whole * per_trace) + " bytes for " + std::to_string(whole) + " traces or " +
            std::to_string(layout.trace0 + (whole + 1) * per_trace) + " bytes for " + std::to_string(whole + 1),
        {path}, "the last trace is incomplete: copy the file again, or check the sample count at byte 3221");
  }
  if (status != SEGY_OK) throw FormatError("cannot count the traces: " + status_text(status), {path});
  return layout;
}

} // namespace geotandem::volume::detail::segy
