#pragma once
// The (inline, crossline) grid of a post-stack SEG-Y file: sorting, line counts and numbers, read
// from the trace headers at chosen byte positions. When the positions asked for do not describe
// a regular grid, the common alternatives are tried so that the error can name the ones that do.

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "geotandem/volume/geometry.hpp"
#include "geotandem/volume/io.hpp"
#include "segy_header.hpp"
#include "segy_layout.hpp"

namespace geotandem::volume::detail::segy {

struct Grid {
  SegyOptions bytes; // where the line numbers (and coordinates) were read
  bool inline_sorted = true;
  // The traces are in no line-after-line order (or some lines are out of order): they are read
  // through Grid::traces, the index built by the pass over every trace header.
  bool unsorted = false;
  int ni = 0, nj = 0;
  // Line numbers: inline of index i is il0 + i * il_step (likewise crosslines).
  int il0 = 0, il_step = 1, xl0 = 0, xl_step = 1;
  // An irregular survey (traces missing from the rectangle of its line numbers): the file's trace
  // at (i, j), row-major, -1 where the file has none. Empty for a full grid, whose traces follow
  // from the sorting.
  std::vector<std::int32_t> traces;
  // Found by the pass over every trace header (an irregular survey, or one padded with
  // placeholders): the affine is then fitted_affine, the least-squares fit of the CDP coordinates
  // of every live trace (its corners may be missing or placeholders), made in that pass; the
  // default grid at the first live trace when the file has no coordinates; may be degenerate.
  // Otherwise the three corners give the affine.
  bool fitted = false;
  SurveyAffine fitted_affine;
  // The first trace of the file that is not a placeholder: its header gives the sample axis.
  int first_live = 0;
  // Placeholders that could not be placed: in an irregular survey they are left out (their bins
  // have no trace); a survey they pad to a full rectangle has them at their places.
  int placeholders_left_out = 0;

  bool irregular() const { return !traces.empty(); }
  // Whether some bin of the rectangle has no trace (its samples are missing).
  bool missing_bins() const { return std::find(traces.begin(), traces.end(), -1) != traces.end(); }
  // The file's trace at (i, j); -1 when the survey has no trace there.
  int trace_of(std::int64_t i, std::int64_t j) const {
    if (irregular()) return traces[static_cast<std::size_t>(i * nj + j)];
    return static_cast<int>(inline_sorted ? i * nj + j : j * ni + i);
  }
  int inline_of(std::int64_t i) const { return static_cast<int>(il0 + i * il_step); }
  int crossline_of(std::int64_t j) const { return static_cast<int>(xl0 + j * xl_step); }
  const char* sorting() const { return unsorted ? "unsorted" : inline_sorted ? "inline-sorted" : "crossline-sorted"; }
};

// The inline (or crossline) number of a trace at its declared field: a whole number within the
// range of int. Throws FormatError naming the file, the trace and the byte otherwise (a float field
// holding 12.5, NaN or 1e12).
int line_number(const TraceHeader& header, const HeaderField& field, const char* what, int trace,
                const std::string& path);

// A placeholder: a trace flagged dead (identification code 2, bytes 29-30) whose line numbers at
// `bytes` are both 0, as some programs pad a survey to a full rectangle. It has no place of its
// own: in a full grid its place in the file is its bin, and its samples are read as written.
bool placeholder(const TraceHeader& header, const SegyOptions& bytes);

// The header of trace (i, j) must carry the line numbers of (i, j); anything else means the file
// is not the regular sorted grid its first traces announced, and samples would land in the wrong
// place. Throws FormatError.
void check_position(const TraceHeader& header, const Grid& grid, std::int64_t i, std::int64_t j, int trace,
                    const std::string& path);

// Finds the grid at the positions in `bytes`. A full sorted grid is found from its first lines and
// corners. Otherwise, when no other common positions (9/21, 5/21, 17/13, 189/193) describe a full
// grid, every trace header is read: sorted traces with some missing give an irregular grid
// (Grid::traces), returned when `read_missing` (missing samples are read, not refused) and refused
// otherwise, naming what is missing; placeholders that pad the survey to its full rectangle give a
// full grid (fitted); traces in no line-after-line order give an unsorted grid read through its
// index (Grid::traces, 4 bytes per bin; the pass keeps 12 bytes per trace while it runs). Two traces
// in one bin are refused with a DataError naming both trace numbers. Pre-stack and unreadable files
// are refused with a FormatError that names the positions that would work, and how to pass them.
// `progress` (may be null) follows the pass over every trace header, when one is needed.
Grid find_grid(const HeaderFile& headers, const Layout& layout, const SegyOptions& bytes, bool read_missing,
               const std::string& path, Progress* progress = nullptr);

// What an irregular grid lacks, for messages: "62 of 63 traces (7 inlines x 9 crosslines); the
// first missing: inline 106, crossline 300". Empty for a full grid.
std::string missing_text(const Grid& grid);

} // namespace geotandem::volume::detail::segy
