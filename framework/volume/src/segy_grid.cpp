// Sorting, line counts and line numbers of a post-stack SEG-Y file, at chosen header positions.

#include "segy_grid.hpp"

#include <optional>
#include <vector>

#include "geotandem/core/error.hpp"

namespace geotandem::volume::detail::segy {
namespace {

// Where line numbers are found in practice, besides SEG-Y rev 1's 189/193: field record and CDP
// ensemble (9/21), trace number in file and CDP (5/21), source and energy source point (17/13).
constexpr std::array<SegyOptions, 4> kCommonBytes{{{189, 193}, {9, 21}, {5, 21}, {17, 13}}};

// Why a choice of positions does not give a regular grid.
struct Problem {
  std::string message;
  std::string hint;
};

struct Probe {
  std::optional<Grid> grid;
  Problem problem;
};

std::string pair_text(const SegyOptions& b) {
  return std::to_string(b.inline_byte) + "/" + std::to_string(b.crossline_byte);
}

std::string how_to_pass(const SegyOptions& b) {
  return "pass --inline-byte " + std::to_string(b.inline_byte) + " --crossline-byte " +
         std::to_string(b.crossline_byte) +
         " on the command line, or segy: {inline_byte: " + std::to_string(b.inline_byte) +
         ", crossline_byte: " + std::to_string(b.crossline_byte) + "} in the recipe's input section";
}

Problem misplaced(const TraceHeader& header, const Grid& g, std::int64_t i, std::int64_t j, int trace) {
  const int il = field(header, g.bytes.inline_byte), xl = field(header, g.bytes.crossline_byte);
  return {"trace " + std::to_string(trace) + " holds inline " + std::to_string(il) + ", crossline " +
              std::to_string(xl) + " (bytes " + pair_text(g.bytes) + ") where a regular " + g.sorting() + " cube of " +
              std::to_string(g.ni) + " x " + std::to_string(g.nj) + " traces has inline " +
              std::to_string(g.inline_of(i)) + ", crossline " + std::to_string(g.crossline_of(j)),
          "the traces are not a regular grid: sort them by inline then crossline and pad missing traces before "
          "reading the file with geotandem"};
}

// Evenly spaced line numbers give the step; anything else is described.
std::optional<Problem> regular_step(const std::vector<int>& numbers, const char* what, int& step) {
  step = numbers.size() > 1 ? numbers[1] - numbers[0] : 1;
  for (std::size_t n = 1; n < numbers.size(); ++n)
    if (step == 0 || numbers[n] - numbers[n - 1] != step)
      return Problem{std::string(what) + " numbers are not evenly spaced: " + std::to_string(numbers[n - 1]) +
                         " then " + std::to_string(numbers[n]) + " after a step of " + std::to_string(step),
                     "geotandem needs a regular grid: pad the missing lines with dead traces"};
  return std::nullopt;
}

// Reads the grid at `bytes` without throwing for what the positions imply; only I/O failures
// of the corner headers throw.
Probe probe(segy_file* file, const Layout& layout, const SegyOptions& bytes, const std::string& path) {
  const int il = bytes.inline_byte, xl = bytes.crossline_byte;
  const long t0 = layout.trace0;
  const int tb = layout.trace_bytes;
  Grid g;
  g.bytes = bytes;
  const TraceHeader first = read_header(file, layout, 0, path);
  const TraceHeader last = read_header(file, layout, layout.traces - 1, path);
  if (field(first, il) == 0 && field(first, xl) == 0 && field(last, il) == 0 && field(last, xl) == 0)
    return {std::nullopt,
            {"no line numbers at bytes " + pair_text(bytes) + ": the first and the last trace hold 0 at both", ""}};
  int sorting = SEGY_UNKNOWN_SORTING;
  int status = segy_sorting(file, il, xl, SEGY_TR_OFFSET, &sorting, t0, tb);
  if (status != SEGY_OK || sorting == SEGY_UNKNOWN_SORTING)
    return {std::nullopt,
            {"the traces are sorted neither by inline (byte " + std::to_string(il) + ") nor by crossline (byte " +
                 std::to_string(xl) + ")",
             "geotandem reads post-stack 3D cubes; sort the traces by inline then crossline"}};
  g.inline_sorted = sorting == SEGY_INLINE_SORTING;

  int offsets = 1;
  status = segy_offsets(file, il, xl, layout.traces, &offsets, t0, tb);
  if (status != SEGY_OK || offsets != 1)
    return {std::nullopt,
            {"pre-stack data: " + std::to_string(offsets) + " traces share each (inline, crossline) bin (bytes " +
                 pair_text(bytes) + "; offsets at byte 37)",
             "geotandem needs a post-stack cube: stack the gathers or extract one offset first"}};

  int inlines = 0, crosslines = 0;
  status = segy_lines_count(file, il, xl, sorting, offsets, &inlines, &crosslines, t0, tb);
  if (status != SEGY_OK || inlines < 1 || crosslines < 1 ||
      static_cast<long long>(inlines) * crosslines != layout.traces)
    return {std::nullopt,
            {"irregular survey: " + std::to_string(layout.traces) + " traces, but the first lines give " +
                 std::to_string(inlines) + " inlines x " + std::to_string(crosslines) + " crosslines (bytes " +
                 pair_text(bytes) + "); traces are missing, lines differ in length, or the file was cut short",
             "pad the cube to a full rectangle of traces, with dead traces where data is missing, before reading "
             "it"}};
  g.ni = inlines;
  g.nj = crosslines;

  std::vector<int> il_numbers(static_cast<std::size_t>(inlines)), xl_numbers(static_cast<std::size_t>(crosslines));
  if (segy_inline_indices(file, il, sorting, inlines, crosslines, offsets, il_numbers.data(), t0, tb) != SEGY_OK ||
      segy_crossline_indices(file, xl, sorting, inlines, crosslines, offsets, xl_numbers.data(), t0, tb) != SEGY_OK)
    return {std::nullopt, {"cannot read the inline and crossline numbers at bytes " + pair_text(bytes), ""}};
  g.il0 = il_numbers.front();
  g.xl0 = xl_numbers.front();
  if (auto p = regular_step(il_numbers, "inline", g.il_step)) return {std::nullopt, *p};
  if (auto p = regular_step(xl_numbers, "crossline", g.xl_step)) return {std::nullopt, *p};

  // The corners: checking their line numbers catches most irregular files at open time rather
  // than at the first read.
  for (auto [i, j] : {std::array<int, 2>{0, 0}, {g.ni - 1, 0}, {0, g.nj - 1}, {g.ni - 1, g.nj - 1}}) {
    const int trace = g.trace_of(i, j);
    const TraceHeader header = read_header(file, layout, trace, path);
    if (field(header, il) != g.inline_of(i) || field(header, xl) != g.crossline_of(j))
      return {std::nullopt, misplaced(header, g, i, j, trace)};
  }
  return {g, {}};
}

} // namespace

int field(const TraceHeader& header, int position) {
  std::int32_t value = 0;
  segy_get_field(header.data(), position, &value);
  return value;
}

TraceHeader read_header(segy_file* file, const Layout& layout, int trace, const std::string& path) {
  TraceHeader header{};
  if (int status = segy_traceheader(file, trace, header.data(), layout.trace0, layout.trace_bytes); status != SEGY_OK)
    throw IoError("cannot read the header of trace " + std::to_string(trace) + ": " + status_text(status), {path});
  return header;
}

void check_position(const TraceHeader& header, const Grid& grid, std::int64_t i, std::int64_t j, int trace,
                    const std::string& path) {
  if (field(header, grid.bytes.inline_byte) == grid.inline_of(i) &&
      field(header, grid.bytes.crossline_byte) == grid.crossline_of(j))
    return;
  Problem p = misplaced(header, grid, i, j, trace);
  throw FormatError(p.message, {path}, p.hint);
}

void check_header_bytes(const SegyOptions& bytes, const std::string& path) {
  TraceHeader blank{};
  std::int32_t value = 0;
  for (auto [position, what] : {std::pair{bytes.inline_byte, "inline"}, {bytes.crossline_byte, "crossline"}})
    if (segy_get_field(blank.data(), position, &value) != SEGY_OK)
      throw InvalidArgument(std::string("the ") + what + " byte position " + std::to_string(position) +
                                " is not the first byte of a trace header field",
                            {path},
                            "line numbers are 4-byte integers at 1-based positions such as 189/193 (SEG-Y rev 1), "
                            "9/21, 5/21 or 17/13");
  if (bytes.inline_byte == bytes.crossline_byte)
    throw InvalidArgument("the inline and crossline byte positions are both " + std::to_string(bytes.inline_byte),
                          {path}, "give two different positions, for example 189 and 193");
}

Grid find_grid(segy_file* file, const Layout& layout, const SegyOptions& bytes, const std::string& path) {
  check_header_bytes(bytes, path);
  Probe asked = probe(file, layout, bytes, path);
  if (asked.grid) return *asked.grid;

  // Try the other common positions: the first that describes a regular grid is the advice.
  std::vector<std::string> tried;
  for (const SegyOptions& other : kCommonBytes) {
    if (other == bytes) continue;
    Probe p = probe(file, layout, other, path);
    // A single line is what a sequence number beside a constant gives: no advice for a cube.
    if (p.grid && p.grid->ni > 1 && p.grid->nj > 1)
      throw FormatError(asked.problem.message + "; the line numbers at bytes " + pair_text(other) +
                            " do describe a regular " + p.grid->sorting() + " grid of " + std::to_string(p.grid->ni) +
                            " inlines x " + std::to_string(p.grid->nj) + " crosslines",
                        {path}, "try them: " + how_to_pass(other));
    tried.push_back(pair_text(other));
  }
  std::string also = "bytes ";
  for (std::size_t n = 0; n < tried.size(); ++n)
    also += (n == 0 ? "" : n + 1 == tried.size() ? " and " : ", ") + tried[n];
  also += " do not describe a regular grid either; if the line numbers are elsewhere, pass their positions with "
          "--inline-byte and --crossline-byte, or segy: {inline_byte: N, crossline_byte: M} in the recipe's input "
          "section";
  throw FormatError(asked.problem.message, {path},
                    asked.problem.hint.empty() ? also : asked.problem.hint + "; " + also);
}

} // namespace geotandem::volume::detail::segy
