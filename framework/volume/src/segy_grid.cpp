// Sorting, line counts and line numbers of a post-stack SEG-Y file, at chosen header positions.

#include "segy_grid.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <optional>
#include <vector>

#include "geotandem/core/error.hpp"
#include "segy_coordinates.hpp"

namespace geotandem::volume::detail::segy {
namespace {

// Where line numbers are found in practice, besides SEG-Y rev 1's 189/193: field record and CDP
// ensemble (9/21), trace number in file and CDP (5/21), source and energy source point (17/13).
constexpr std::array<SegyOptions, 4> kCommonBytes{{{189, 193}, {9, 21}, {5, 21}, {17, 13}}};

// Why a choice of positions does not give a regular grid; `scan`: reading every trace header may
// still find a sorted survey with traces missing.
struct Problem {
  std::string message;
  std::string hint;
  bool scan = false;
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
          "reading the file with geotandem",
          true};
}

// Evenly spaced line numbers give the step; anything else is described.
std::optional<Problem> regular_step(const std::vector<int>& numbers, const char* what, int& step) {
  // Differences in 64 bits: two numbers far apart differ by more than an int holds.
  const std::int64_t first = numbers.size() > 1 ? std::int64_t{numbers[1]} - numbers[0] : 1;
  for (std::size_t n = 1; n < numbers.size(); ++n)
    if (first == 0 || std::int64_t{numbers[n]} - numbers[n - 1] != first)
      return Problem{std::string(what) + " numbers are not evenly spaced: " + std::to_string(numbers[n - 1]) +
                         " then " + std::to_string(numbers[n]) + " after a step of " + std::to_string(first),
                     "geotandem needs a regular grid: pad the missing lines with dead traces", true};
  if (first < std::numeric_limits<int>::min() || first > std::numeric_limits<int>::max())
    return Problem{std::string(what) + " numbers " + std::to_string(numbers[0]) + " and " + std::to_string(numbers[1]) +
                       " are too far apart to be neighbouring lines",
                   "check the header bytes of the line numbers", true};
  step = static_cast<int>(first);
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
            {"no line numbers at bytes " + pair_text(bytes) + ": the first and the last trace hold 0 at both", "",
             placeholder(first, bytes) || placeholder(last, bytes)}};
  int sorting = SEGY_UNKNOWN_SORTING;
  int status = segy_sorting(file, il, xl, SEGY_TR_OFFSET, &sorting, t0, tb);
  if (status != SEGY_OK || sorting == SEGY_UNKNOWN_SORTING)
    return {std::nullopt,
            {"the traces are sorted neither by inline (byte " + std::to_string(il) + ") nor by crossline (byte " +
                 std::to_string(xl) + ")",
             "geotandem reads post-stack 3D cubes; sort the traces by inline then crossline", true}};
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
             "it",
             true}};
  g.ni = inlines;
  g.nj = crosslines;

  std::vector<int> il_numbers(static_cast<std::size_t>(inlines)), xl_numbers(static_cast<std::size_t>(crosslines));
  if (segy_inline_indices(file, il, sorting, inlines, crosslines, offsets, il_numbers.data(), t0, tb) != SEGY_OK ||
      segy_crossline_indices(file, xl, sorting, inlines, crosslines, offsets, xl_numbers.data(), t0, tb) != SEGY_OK)
    return {std::nullopt, {"cannot read the inline and crossline numbers at bytes " + pair_text(bytes), "", true}};
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

// Whether the traces run through the file line after line: the line numbers of `outer` never turn
// back, and within a line those of `inner` go one way without repeating.
template <class Outer, class Inner>
bool sorted_by(const std::vector<std::array<int, 2>>& bins, Outer outer, Inner inner) {
  int outer_way = 0, inner_way = 0;
  for (std::size_t n = 1; n < bins.size(); ++n) {
    const int a = outer(bins[n - 1]), b = outer(bins[n]);
    if (a != b) {
      const int way = b > a ? 1 : -1;
      if (outer_way != 0 && way != outer_way) return false;
      outer_way = way;
      inner_way = 0;
      continue;
    }
    const int x = inner(bins[n - 1]), y = inner(bins[n]);
    if (x == y) return false;
    const int way = y > x ? 1 : -1;
    if (inner_way != 0 && way != inner_way) return false;
    inner_way = way;
  }
  return true;
}

// The step of a set of line numbers: the greatest common divisor of their differences (1 for one
// line). Sorts and deduplicates `numbers`.
std::int64_t line_step(std::vector<int>& numbers) {
  std::sort(numbers.begin(), numbers.end());
  numbers.erase(std::unique(numbers.begin(), numbers.end()), numbers.end());
  std::int64_t step = 0;
  for (std::size_t n = 1; n < numbers.size(); ++n)
    step = std::gcd(step, std::int64_t{numbers[n]} - numbers[n - 1]);
  return step == 0 ? 1 : step;
}

// Every trace header read: a survey whose sorted traces leave bins of its rectangle empty. The
// rectangle is spanned by the smallest and largest line numbers at the common step; a rectangle
// more than ten times the traces is not taken for a survey (wrong header bytes, most likely). The
// same pass fits the affine to the traces' coordinates.
Probe scan(segy_file* file, const Layout& layout, const SegyOptions& bytes, const std::string& path,
           Progress* progress) {
  // The live traces (placeholders have no line numbers) and their bins, in file order.
  std::vector<int> live;
  std::vector<std::array<int, 2>> bins;
  CoordinateFit coordinates;
  std::optional<TraceCoordinates> frame; // from the first live trace
  NullProgress silent;
  Progress& report = progress ? *progress : silent;
  report.begin("reading trace headers", static_cast<std::uint64_t>(layout.traces), "traces");
  struct StopUnlessEnded {
    Progress& report;
    bool ended = false;
    ~StopUnlessEnded() {
      if (!ended) report.stop();
    }
  } guard{report};
  for (int t = 0; t < layout.traces; ++t) {
    if (t % 65536 == 0) report.update(static_cast<std::uint64_t>(t));
    const TraceHeader header = read_header(file, layout, t, path);
    if (placeholder(header, bytes)) continue;
    if (!frame) frame.emplace(header);
    const std::array<int, 2> bin{field(header, bytes.inline_byte), field(header, bytes.crossline_byte)};
    live.push_back(t);
    bins.push_back(bin);
    coordinates.add(std::int64_t{bin[0]} - bins[0][0], std::int64_t{bin[1]} - bins[0][1], frame->xy(header));
  }
  report.update(static_cast<std::uint64_t>(layout.traces));
  report.end();
  guard.ended = true;
  if (live.empty())
    return {std::nullopt, {"reading every trace header: every trace is a placeholder (dead, line numbers 0)", ""}};
  Grid g;
  g.bytes = bytes;
  g.fitted = true;
  g.first_live = live.front();
  const auto il_of = [](const std::array<int, 2>& b) { return b[0]; };
  const auto xl_of = [](const std::array<int, 2>& b) { return b[1]; };
  g.inline_sorted = sorted_by(bins, il_of, xl_of);
  if (!g.inline_sorted && !sorted_by(bins, xl_of, il_of))
    return {std::nullopt,
            {"reading every trace header: the traces are not sorted line after line (or several share a bin)", ""}};
  std::vector<int> il_numbers(bins.size()), xl_numbers(bins.size());
  std::transform(bins.begin(), bins.end(), il_numbers.begin(), il_of);
  std::transform(bins.begin(), bins.end(), xl_numbers.begin(), xl_of);
  const std::int64_t il_step = line_step(il_numbers), xl_step = line_step(xl_numbers);
  const std::int64_t ni = (std::int64_t{il_numbers.back()} - il_numbers.front()) / il_step + 1;
  const std::int64_t nj = (std::int64_t{xl_numbers.back()} - xl_numbers.front()) / xl_step + 1;
  // Within int range: every line number of the rectangle lies between two numbers of the file.
  if (ni * nj > 10 * static_cast<std::int64_t>(layout.traces) || ni * nj > std::numeric_limits<std::int32_t>::max())
    return {std::nullopt,
            {"reading every trace header: the line numbers at bytes " + pair_text(bytes) + " span " +
                 std::to_string(ni) + " inlines x " + std::to_string(nj) + " crosslines for " +
                 std::to_string(layout.traces) + " traces, too few to be a survey",
             ""}};
  g.il0 = il_numbers.front();
  g.xl0 = xl_numbers.front();
  g.il_step = static_cast<int>(il_step); // at most the span of two ints that passed the test above
  g.xl_step = static_cast<int>(xl_step);
  g.ni = static_cast<int>(ni);
  g.nj = static_cast<int>(nj);
  g.fitted_affine = coordinates.in_indices(double(g.il0) - bins[0][0], double(g.il_step), double(g.xl0) - bins[0][1],
                                           double(g.xl_step));
  const auto bin_of = [&](const std::array<int, 2>& b) {
    const std::int64_t i = (std::int64_t{b[0]} - g.il0) / g.il_step, j = (std::int64_t{b[1]} - g.xl0) / g.xl_step;
    return g.inline_sorted ? i * nj + j : j * ni + i; // in file order, numbers counting up
  };
  // Placeholders padding the survey to its full rectangle: every live trace sits at the place in
  // the file its bin has, so each placeholder's place is its bin too.
  bool padded = ni * nj == layout.traces;
  for (std::size_t n = 0; padded && n < live.size(); ++n)
    padded = bin_of(bins[n]) == live[n];
  if (padded) return {g, {}};
  g.placeholders_left_out = layout.traces - static_cast<int>(live.size());
  g.traces.assign(static_cast<std::size_t>(ni * nj), -1);
  for (std::size_t n = 0; n < live.size(); ++n) {
    const auto [il, xl] = bins[n];
    const std::int64_t i = (std::int64_t{il} - g.il0) / g.il_step, j = (std::int64_t{xl} - g.xl0) / g.xl_step;
    g.traces[static_cast<std::size_t>(i * nj + j)] = live[n]; // sorted: no bin twice
  }
  return {g, {}};
}

} // namespace

std::string missing_text(const Grid& grid) {
  if (!grid.irregular()) return {};
  const auto present = std::count_if(grid.traces.begin(), grid.traces.end(), [](std::int32_t t) { return t >= 0; });
  std::string text = std::to_string(present) + " of " + std::to_string(grid.traces.size()) + " traces (" +
                     std::to_string(grid.ni) + " inlines x " + std::to_string(grid.nj) + " crosslines" +
                     (grid.placeholders_left_out > 0
                          ? "; " + std::to_string(grid.placeholders_left_out) +
                                " placeholders, dead traces with line numbers 0, left out: their bins are not known"
                          : std::string()) +
                     ")";
  // A whole line missing reads best as the jump in the line numbers.
  std::vector<bool> inline_has(static_cast<std::size_t>(grid.ni)), crossline_has(static_cast<std::size_t>(grid.nj));
  for (int i = 0; i < grid.ni; ++i)
    for (int j = 0; j < grid.nj; ++j)
      if (grid.trace_of(i, j) >= 0)
        inline_has[static_cast<std::size_t>(i)] = crossline_has[static_cast<std::size_t>(j)] = true;
  struct Axis {
    const std::vector<bool>& has;
    const char* name;
    int first, step;
  };
  for (const Axis& axis :
       {Axis{inline_has, "inline", grid.il0, grid.il_step}, Axis{crossline_has, "crossline", grid.xl0, grid.xl_step}}) {
    const auto gap = std::find(axis.has.begin(), axis.has.end(), false);
    if (gap == axis.has.end()) continue;
    // The first and the last line hold traces (they span the rectangle): the gap has both sides.
    const auto at = static_cast<int>(gap - axis.has.begin());
    const auto after = static_cast<int>(std::find(gap, axis.has.end(), true) - axis.has.begin());
    const std::string name = axis.name;
    return text + "; no trace on " + name + " " + std::to_string(axis.first + at * axis.step) + ": the " + name +
           " numbers go " + std::to_string(axis.first + (at - 1) * axis.step) + " then " +
           std::to_string(axis.first + after * axis.step) + " where the step is " + std::to_string(axis.step);
  }
  for (int i = 0; i < grid.ni; ++i)
    for (int j = 0; j < grid.nj; ++j)
      if (grid.trace_of(i, j) < 0)
        return text + "; the first missing: inline " + std::to_string(grid.inline_of(i)) + ", crossline " +
               std::to_string(grid.crossline_of(j));
  return text;
}

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

bool placeholder(const TraceHeader& header, const SegyOptions& bytes) {
  return field(header, SEGY_TR_TRACE_ID) == 2 && field(header, bytes.inline_byte) == 0 &&
         field(header, bytes.crossline_byte) == 0;
}

void check_position(const TraceHeader& header, const Grid& grid, std::int64_t i, std::int64_t j, int trace,
                    const std::string& path) {
  if (field(header, grid.bytes.inline_byte) == grid.inline_of(i) &&
      field(header, grid.bytes.crossline_byte) == grid.crossline_of(j))
    return;
  if (!grid.irregular() && placeholder(header, grid.bytes)) return; // its place in the file is its bin
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

Grid find_grid(segy_file* file, const Layout& layout, const SegyOptions& bytes, bool read_missing,
               const std::string& path, Progress* progress) {
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
  const std::string hint = asked.problem.hint.empty() ? also : asked.problem.hint + "; " + also;
  // No positions give a full grid from a few headers: the traces at the asked ones may be a survey
  // with some missing, read when missing samples are (the NaN fill policy) and refused otherwise,
  // or one padded with placeholders, read.
  if (!asked.problem.scan) throw FormatError(asked.problem.message, {path}, hint);
  Probe scanned = scan(file, layout, bytes, path, progress);
  if (!scanned.grid) throw FormatError(asked.problem.message + "; " + scanned.problem.message, {path}, hint);
  // Read: a survey padded with placeholders, or one whose every bin has a trace (placeholders
  // elsewhere in the file), or with missing samples read.
  if (read_missing || !scanned.grid->missing_bins()) return *scanned.grid;
  throw FormatError("irregular survey at bytes " + pair_text(bytes) + ": " + missing_text(*scanned.grid) +
                        " (traces are missing where the survey has none, or the file was cut short)",
                    {path},
                    "read the missing traces as missing samples with --nan fill (input.nan: fill in a recipe): "
                    "outside every body, dead traces under attributes; or pad the cube to a full rectangle of "
                    "traces with dead traces");
}

} // namespace geotandem::volume::detail::segy
