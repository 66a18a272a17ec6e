#pragma once
// The (inline, crossline) grid of a post-stack SEG-Y file: sorting, line counts and numbers, read
// from the trace headers at chosen byte positions. When the positions asked for do not describe
// a regular grid, the common alternatives are tried so that the error can name the ones that do.

#include <array>
#include <cstdint>
#include <string>

#include "geotandem/volume/io.hpp"
#include "segy_layout.hpp"

namespace geotandem::volume::detail::segy {

using TraceHeader = std::array<char, SEGY_TRACE_HEADER_SIZE>;

struct Grid {
  SegyOptions bytes; // where the line numbers were read
  bool inline_sorted = true;
  int ni = 0, nj = 0;
  // Line numbers: inline of index i is il0 + i * il_step (likewise crosslines).
  int il0 = 0, il_step = 1, xl0 = 0, xl_step = 1;

  int trace_of(std::int64_t i, std::int64_t j) const {
    return static_cast<int>(inline_sorted ? i * nj + j : j * ni + i);
  }
  int inline_of(std::int64_t i) const { return static_cast<int>(il0 + i * il_step); }
  int crossline_of(std::int64_t j) const { return static_cast<int>(xl0 + j * xl_step); }
  const char* sorting() const { return inline_sorted ? "inline-sorted" : "crossline-sorted"; }
};

// The 4-byte integer (or 2-byte, for such fields) at 1-based byte `position` of a trace header.
int field(const TraceHeader& header, int position);

// Throws IoError naming the trace when its header cannot be read.
TraceHeader read_header(segy_file* file, const Layout& layout, int trace, const std::string& path);

// The header of trace (i, j) must carry the line numbers of (i, j); anything else means the file
// is not the regular sorted grid its first traces announced, and samples would land in the wrong
// place. Throws FormatError.
void check_position(const TraceHeader& header, const Grid& grid, std::int64_t i, std::int64_t j, int trace,
                    const std::string& path);

// Throws InvalidArgument unless both positions start a trace header field segyio can read.
void check_header_bytes(const SegyOptions& bytes, const std::string& path);

// Finds the grid at the positions in `bytes`; refuses pre-stack, unsorted and irregular files
// with a FormatError that names the common positions (9/21, 5/21, 17/13, 189/193) that would
// describe a regular grid, and how to pass them.
Grid find_grid(segy_file* file, const Layout& layout, const SegyOptions& bytes, const std::string& path);

} // namespace geotandem::volume::detail::segy
