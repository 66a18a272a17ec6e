// Sorting, line counts and line numbers of a post-stack SEG-Y file, at chosen header positions.

#include "segy_grid.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <optional>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/core/params.hpp"
#include "segy_coordinates.hpp"

namespace geotandem::volume::detail::segy {
namespace {

// Where line numbers are found in practice, besides SEG-Y rev 1's 189/193: field record and CDP
// ensemble (9/21), trace number in file and CDP (5/21), source and energy source point (17/13).
constexpr std::array<std::array<int, 2>, 4> kCommonBytes{{{189, 193}, {9, 21}, {5, 21}, {17, 13}}};

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
  std::string text = std::to_string(b.inline_byte) + "/" + std::to_string(b.crossline_byte);
  if (b.inline_type != HeaderType::int32 || b.crossline_type != HeaderType::int32)
    text += std::string(" as ") + to_string(b.inline_type) + "/" + to_string(b.crossline_type);
  return text;
}

std::string how_to_pass(const SegyOptions& b) {
  return "pass --inline-byte " + std::to_string(b.inline_byte) + " --crossline-byte " +
         std::to_string(b.crossline_byte) +
         " on the command line, or segy: {inline_byte: " + std::to_string(b.inline_byte) +
         ", crossline_byte: " + std::to_string(b.crossline_byte) + "} in the recipe's input section";
}

Problem misplaced(const TraceHeader& header, const Grid& g, std::int64_t i, std::int64_t j, int trace) {
  const double il = value(header, g.bytes.inline_field()), xl = value(header, g.bytes.crossline_field());
  return {"trace " + std::to_string(trace) + " holds inline " + number_text(il) + ", crossline " + number_text(xl) +
              " (bytes " + pair_text(g.bytes) + ") where a regular " + g.sorting() + " cube of " +
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

// Reads the grid at `bytes` from a few headers without throwing for what the positions imply
// (the first line's traces, the first trace of each line, the corners); only I/O failures and line
// numbers that are no integers throw. Sorting: the first two traces share the inline (inline-sorted)
// or the crossline (crossline-sorted); the first line's length gives the other count.
Probe probe(const HeaderFile& headers, const Layout& layout, const SegyOptions& bytes, const std::string& path) {
  const HeaderField il = bytes.inline_field(), xl = bytes.crossline_field();
  Grid g;
  g.bytes = bytes;
  const int n = layout.traces;
  const TraceHeader first = headers.read(0);
  const TraceHeader last = headers.read(n - 1);
  if (value(first, il) == 0 && value(first, xl) == 0 && value(last, il) == 0 && value(last, xl) == 0)
    return {std::nullopt,
            {"no line numbers at bytes " + pair_text(bytes) + ": the first and the last trace hold 0 at both", "",
             placeholder(first, bytes) || placeholder(last, bytes)}};
  auto bin = [&](int trace) {
    const TraceHeader h = trace == 0 ? first : headers.read(trace);
    return std::array<int, 2>{line_number(h, il, "inline", trace, path), line_number(h, xl, "crossline", trace, path)};
  };
  const std::array<int, 2> b0 = bin(0);
  if (n == 1) {
    g.ni = g.nj = 1;
    g.il0 = b0[0];
    g.xl0 = b0[1];
    return {g, {}};
  }
  const std::array<int, 2> b1 = bin(1);
  if (b1 == b0) {
    const TraceHeader second = headers.read(1);
    if (field(second, SEGY_TR_OFFSET) == field(first, SEGY_TR_OFFSET)) // a repeated trace: the scan names it
      return {std::nullopt, {"traces 0 and 1 share one bin (bytes " + pair_text(bytes) + ")", "", true}};
    int offsets = 2;
    while (offsets < n && bin(offsets) == b0)
      ++offsets;
    return {std::nullopt,
            {"pre-stack data: " + std::to_string(offsets) + " traces share each (inline, crossline) bin (bytes " +
                 pair_text(bytes) + "; offsets at byte 37)",
             "geotandem needs a post-stack cube: stack the gathers or extract one offset first"}};
  }
  if (b1[0] != b0[0] && b1[1] != b0[1])
    return {std::nullopt,
            {"the traces are sorted neither by inline (byte " + std::to_string(il.byte) + ") nor by crossline (byte " +
                 std::to_string(xl.byte) + ")",
             "geotandem reads post-stack 3D cubes; sort the traces by inline then crossline", true}};
  g.inline_sorted = b1[0] == b0[0];
  const int outer = g.inline_sorted ? 0 : 1, inner = 1 - outer;
  // The first line: its traces share the outer number.
  std::vector<int> inner_numbers{b0[inner], b1[inner]};
  for (int t = 2; t < n; ++t) {
    const std::array<int, 2> b = bin(t);
    if (b[outer] != b0[outer]) break;
    inner_numbers.push_back(b[inner]);
  }
  const int line = static_cast<int>(inner_numbers.size());
  const int lines = n / line;
  const int inlines = g.inline_sorted ? lines : line, crosslines = g.inline_sorted ? line : lines;
  if (static_cast<long long>(lines) * line != n)
    return {std::nullopt,
            {"irregular survey: " + std::to_string(n) + " traces, but the first lines give " + std::to_string(inlines) +
                 " inlines x " + std::to_string(crosslines) + " crosslines (bytes " + pair_text(bytes) +
                 "); traces are missing, lines differ in length, or the file was cut short",
             "pad the cube to a full rectangle of traces, with dead traces where data is missing, before reading "
             "it",
             true}};
  g.ni = inlines;
  g.nj = crosslines;
  std::vector<int> outer_numbers(static_cast<std::size_t>(lines));
  for (int k = 0; k < lines; ++k)
    outer_numbers[static_cast<std::size_t>(k)] = k == 0 ? b0[outer] : bin(k * line)[outer];
  const std::vector<int>& il_numbers = g.inline_sorted ? outer_numbers : inner_numbers;
  const std::vector<int>& xl_numbers = g.inline_sorted ? inner_numbers : outer_numbers;
  g.il0 = il_numbers.front();
  g.xl0 = xl_numbers.front();
  if (auto p = regular_step(il_numbers, "inline", g.il_step)) return {std::nullopt, *p};
  if (auto p = regular_step(xl_numbers, "crossline", g.xl_step)) return {std::nullopt, *p};

  // The corners: checking their line numbers catches most irregular files at open time rather
  // than at the first read.
  for (auto [i, j] : {std::array<int, 2>{0, 0}, {g.ni - 1, 0}, {0, g.nj - 1}, {g.ni - 1, g.nj - 1}}) {
    const int trace = g.trace_of(i, j);
    const TraceHeader header = headers.read(trace);
    if (value(header, il) != g.inline_of(i) || value(header, xl) != g.crossline_of(j))
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

// Every trace header read: a survey whose traces leave bins of its rectangle empty, or lie in no
// line-after-line order (then read through the index this pass builds). The rectangle is spanned
// by the smallest and largest line numbers at the common step; a rectangle more than ten times the
// traces is not taken for a survey (wrong header bytes, most likely). The same pass fits the affine
// to the traces' coordinates. Memory: 12 bytes per trace while the pass runs, then the grid's 4
// bytes per bin; the samples are never held.
Probe scan(const HeaderFile& headers, const Layout& layout, const SegyOptions& bytes, const std::string& path,
           Progress* progress) {
  // The live traces (placeholders have no line numbers) and their bins, in file order.
  std::vector<int> live;
  std::vector<std::array<int, 2>> bins;
  CoordinateFit coordinates;
  std::optional<TraceCoordinates> frame; // from the first live trace
  NullProgress silent;
  headers.scan(
      [&](int t, const TraceHeader& header) {
        if (placeholder(header, bytes)) return;
        if (!frame) frame.emplace(header, bytes, t, path);
        const std::array<int, 2> bin{line_number(header, bytes.inline_field(), "inline", t, path),
                                     line_number(header, bytes.crossline_field(), "crossline", t, path)};
        live.push_back(t);
        bins.push_back(bin);
        coordinates.add(std::int64_t{bin[0]} - bins[0][0], std::int64_t{bin[1]} - bins[0][1],
                        frame->xy(header, t, path));
      },
      progress ? *progress : silent);
  if (live.empty())
    return {std::nullopt, {"reading every trace header: every trace is a placeholder (dead, line numbers 0)", ""}};
  Grid g;
  g.bytes = bytes;
  g.fitted = true;
  g.first_live = live.front();
  const auto il_of = [](const std::array<int, 2>& b) { return b[0]; };
  const auto xl_of = [](const std::array<int, 2>& b) { return b[1]; };
  g.inline_sorted = sorted_by(bins, il_of, xl_of);
  g.unsorted = !g.inline_sorted && !sorted_by(bins, xl_of, il_of);
  if (g.unsorted) g.inline_sorted = true;
  std::int64_t il_step = 0, xl_step = 0;
  std::int64_t il_first = 0, il_last = 0, xl_first = 0, xl_last = 0;
  {
    std::vector<int> numbers(bins.size());
    std::transform(bins.begin(), bins.end(), numbers.begin(), il_of);
    il_step = line_step(numbers);
    il_first = numbers.front();
    il_last = numbers.back();
    numbers.assign(bins.size(), 0);
    std::transform(bins.begin(), bins.end(), numbers.begin(), xl_of);
    xl_step = line_step(numbers);
    xl_first = numbers.front();
    xl_last = numbers.back();
  }
  const std::int64_t ni = (il_last - il_first) / il_step + 1;
  const std::int64_t nj = (xl_last - xl_first) / xl_step + 1;
  // Within int range: every line number of the rectangle lies between two numbers of the file.
  // Each count is tested before their product, which overflows for spans near 2^32 (fuzz_segy_header).
  const std::int64_t most = std::numeric_limits<std::int32_t>::max();
  if (ni > most || nj > most || ni * nj > 10 * static_cast<std::int64_t>(layout.traces) || ni * nj > most)
    return {std::nullopt,
            {"reading every trace header: the line numbers at bytes " + pair_text(bytes) + " span " +
                 std::to_string(ni) + " inlines x " + std::to_string(nj) + " crosslines for " +
                 std::to_string(layout.traces) + " traces, too few to be a survey",
             ""}};
  g.il0 = static_cast<int>(il_first);
  g.xl0 = static_cast<int>(xl_first);
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
  bool padded = !g.unsorted && ni * nj == layout.traces;
  for (std::size_t n = 0; padded && n < live.size(); ++n)
    padded = bin_of(bins[n]) == live[n];
  if (padded) return {g, {}};
  g.placeholders_left_out = layout.traces - static_cast<int>(live.size());
  g.traces.assign(static_cast<std::size_t>(ni * nj), -1);
  for (std::size_t n = 0; n < live.size(); ++n) {
    const auto [il, xl] = bins[n];
    const std::int64_t i = (std::int64_t{il} - g.il0) / g.il_step, j = (std::int64_t{xl} - g.xl0) / g.xl_step;
    std::int32_t& place = g.traces[static_cast<std::size_t>(i * nj + j)];
    if (place >= 0)
      throw DataError("traces " + std::to_string(place) + " and " + std::to_string(live[n]) + " both hold inline " +
                          std::to_string(il) + ", crossline " + std::to_string(xl) + " (trace header bytes " +
                          pair_text(bytes) + ")",
                      {path},
                      "a post-stack cube has one trace per bin: remove the duplicated trace, or check the byte "
                      "positions of the line numbers");
    place = live[n];
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

int line_number(const TraceHeader& header, const HeaderField& f, const char* what, int trace, const std::string& path) {
  const double v = value(header, f);
  if (v == std::nearbyint(v) && v >= std::numeric_limits<int>::min() && v <= std::numeric_limits<int>::max())
    return static_cast<int>(v);
  throw FormatError("trace " + std::to_string(trace) + " holds " + number_text(v) + " as its " + what +
                        " number (trace header byte " + std::to_string(f.byte) + ", " + to_string(f.type) +
                        "): not a whole number",
                    {path},
                    std::string("check the byte and type of the ") + what + " numbers (--" + what + "-byte, --" + what +
                        "-type; segy: {" + what + "_byte, " + what + "_type} in a recipe)");
}

bool placeholder(const TraceHeader& header, const SegyOptions& bytes) {
  return field(header, SEGY_TR_TRACE_ID) == 2 && value(header, bytes.inline_field()) == 0 &&
         value(header, bytes.crossline_field()) == 0;
}

void check_position(const TraceHeader& header, const Grid& grid, std::int64_t i, std::int64_t j, int trace,
                    const std::string& path) {
  if (value(header, grid.bytes.inline_field()) == grid.inline_of(i) &&
      value(header, grid.bytes.crossline_field()) == grid.crossline_of(j))
    return;
  if (!grid.irregular() && placeholder(header, grid.bytes)) return; // its place in the file is its bin
  Problem p = misplaced(header, grid, i, j, trace);
  throw FormatError(p.message, {path}, p.hint);
}

Grid find_grid(const HeaderFile& headers, const Layout& layout, const SegyOptions& bytes, bool read_missing,
               const std::string& path, Progress* progress) {
  check_segy_options(bytes, path);
  Probe asked = probe(headers, layout, bytes, path);
  if (asked.grid) return *asked.grid;

  // Try the other common positions: the first that describes a regular grid is the advice.
  std::vector<std::string> tried;
  for (const auto& [inline_at, crossline_at] : kCommonBytes) {
    const SegyOptions other = bytes.with_lines(inline_at, crossline_at);
    if (other == bytes) continue;
    Probe p = probe(headers, layout, other, path);
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
  Probe scanned = scan(headers, layout, bytes, path, progress);
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
