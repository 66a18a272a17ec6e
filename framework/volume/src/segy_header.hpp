#pragma once
// Trace headers as the file holds them: 240 bytes in the file's byte order, read by geotandem
// itself (not through segyio, whose header functions know only the standard's field starts and
// swap little-endian headers field by field, which scrambles a field at an unassigned byte such as
// 221). Fields are decoded at any byte with a declared type.

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "geotandem/core/progress.hpp"
#include "geotandem/volume/segy_options.hpp"
#include "segy_layout.hpp"

namespace geotandem::volume::detail::segy {

struct TraceHeader {
  std::array<unsigned char, SEGY_TRACE_HEADER_SIZE> bytes{};
  bool little_endian = false;
};

// The field of `type` at 1-based `byte`, as a double (exact for the integers; the floats widened).
// Precondition: the field lies within the header (check_segy_options).
double value(const TraceHeader& header, const HeaderField& field);
// A standard field of SEG-Y rev 1 at 1-based `position`, with the standard's width (2 or 4 bytes)
// and signed integer type: 29 (trace identification), 71 (coordinate scalar), 89, 109, 115, 117,
// 215 are 2 bytes; the rest are read as 4.
int field(const TraceHeader& header, int position);

// IBM System/360 single-precision float (big-endian bit pattern as a 32-bit integer) to double.
double ibm_to_double(std::uint32_t bits);

// Reads trace headers from the file by position (pread on its own descriptor, so that it never
// moves segyio's file position). Copyable handles share the descriptor.
class HeaderFile {
public:
  // Throws IoError naming `path` when the file cannot be opened.
  HeaderFile(const std::string& path, const Layout& layout);
  // Throws IoError naming the file and the trace when the header cannot be read.
  TraceHeader read(int trace) const;
  // Every header from the first trace to the last, in file order, read in large sequential chunks
  // (a few MiB at a time: the headers of a million traces in a second or so when cached). Reports
  // to `progress` as "reading trace headers".
  void scan(const std::function<void(int, const TraceHeader&)>& visit, Progress& progress) const;
  const std::string& path() const { return path_; }

private:
  struct Fd;
  std::shared_ptr<Fd> fd_;
  std::string path_;
  Layout layout_;
};

} // namespace geotandem::volume::detail::segy
