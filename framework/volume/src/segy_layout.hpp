#pragma once
// How a SEG-Y file lays out its traces, from the binary header: byte order, sample format, sizes.
// Shared by the SEG-Y reader's parts (segy.cpp, segy_grid.cpp).

#include <string>

#include "segy_file.hpp"

namespace geotandem::volume::detail::segy {

struct Layout {
  long trace0 = 0;            // byte offset of the first trace header
  int trace_bytes = 0;        // bytes of samples per trace, header excluded
  int format = 0;             // SEGY_FORMAT code (binary header byte 3225)
  bool little_endian = false; // detected from the format code's byte order
  int traces = 0;
  int samples = 0;  // per trace
  int interval = 0; // binary header byte 3217: microseconds (or millimetres in our depth files)
  // SEG-Y revision, binary header bytes 3501 (major) and 3502 (minor): 0.0 for files before rev 1.
  int revision_major = 0, revision_minor = 0;
  int extended_textual = 0; // 3200-byte extended textual headers (byte 3505)
  // Rev 2: 240-byte trace header extensions after each standard trace header (bytes 3507-3510).
  int header_extensions = 0;
  // Binary header bytes 3255-3256: 1 metres, 2 feet, anything else not given.
  int measurement_system = 0;

  // Bytes from one trace's header to the next's.
  long long stride() const { return SEGY_TRACE_HEADER_SIZE * (1ll + header_extensions) + trace_bytes; }
  long long header_offset(int trace) const { return trace0 + stride() * trace; }
  // What segyio is told, so that its sample reads skip the header extensions: the samples of
  // trace t start at segyio_trace0() + t * (segyio_trace_bytes() + 240) + 240.
  long segyio_trace0() const { return trace0 + static_cast<long>(SEGY_TRACE_HEADER_SIZE) * header_extensions; }
  int segyio_trace_bytes() const { return trace_bytes + SEGY_TRACE_HEADER_SIZE * header_extensions; }
  std::string revision_text() const;

  int sample_size() const; // bytes per sample: 4, 2 or 1
  // The format code with segyio's byte-order flag, for segy_set_format.
  int segyio_format() const;
};

// "IBM float", "16-bit integer", ...; "unknown" for codes SEG-Y does not define.
const char* sample_format_name(int format);
inline const char* byte_order_name(bool little_endian) {
  return little_endian ? "little-endian" : "big-endian";
}

// Reads the binary header in either byte order (the sample format code at byte 3225 is a small
// number only in the file's own order), tells segyio the format and byte order, and checks that
// the file holds whole traces. Throws FormatError naming `path` for unsupported formats,
// unreadable headers and truncated files.
Layout read_layout(segy_file* file, const std::string& path);

} // namespace geotandem::volume::detail::segy
