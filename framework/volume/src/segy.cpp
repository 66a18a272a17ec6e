// SEG-Y reader: a post-stack 3D cube, inline- or crossline-sorted, IBM or IEEE floats, read
// trace by trace through segyio. Opening reads the headers only; read_box reads the traces of the
// box and nothing else.

#include <array>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <vector>

#include "formats.hpp"
#include "geotandem/core/error.hpp"
#include "segy_file.hpp"

namespace geotandem::volume::detail {
namespace {

using TraceHeader = std::array<char, SEGY_TRACE_HEADER_SIZE>;

const char* sample_format_name(int format) {
  switch (format) {
  case SEGY_IBM_FLOAT_4_BYTE: return "IBM float";
  case SEGY_SIGNED_INTEGER_4_BYTE: return "32-bit integer";
  case SEGY_SIGNED_SHORT_2_BYTE: return "16-bit integer";
  case SEGY_FIXED_POINT_WITH_GAIN_4_BYTE: return "fixed point with gain";
  case SEGY_IEEE_FLOAT_4_BYTE: return "IEEE float";
  case SEGY_SIGNED_CHAR_1_BYTE: return "8-bit integer";
  default: return "unknown";
  }
}

int field(const TraceHeader& header, int position) {
  std::int32_t value = 0;
  segy_get_field(header.data(), position, &value);
  return value;
}

// Where the samples of trace (i, j) are, and how they are encoded.
struct Layout {
  long trace0 = 0;     // byte offset of the first trace header
  int trace_bytes = 0; // bytes of samples per trace, header excluded
  int format = 0;      // SEGY_FORMAT code
  int traces = 0;
  int samples = 0;  // per trace
  int interval = 0; // binary header byte 3217: microseconds (or millimetres in our depth files)
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

TraceHeader read_header(segy_file* file, const Layout& layout, int trace, const std::string& path) {
  TraceHeader header{};
  if (int status = segy_traceheader(file, trace, header.data(), layout.trace0, layout.trace_bytes); status != SEGY_OK)
    throw IoError("cannot read the header of trace " + std::to_string(trace) + ": " + segy::status_text(status),
                  {path});
  return header;
}

// The header of trace (i, j) must carry the line numbers of (i, j); anything else means the file
// is not the regular sorted grid its first traces announced, and samples would land in the
// wrong place.
void check_position(const TraceHeader& header, const Layout& layout, std::int64_t i, std::int64_t j, int trace,
                    const std::string& path) {
  int il = field(header, segy::kInlineField), xl = field(header, segy::kCrosslineField);
  if (il == layout.inline_of(i) && xl == layout.crossline_of(j)) return;
  throw FormatError("trace " + std::to_string(trace) + " holds inline " + std::to_string(il) + ", crossline " +
                        std::to_string(xl) + " where a regular " + layout.sorting() + " cube of " +
                        std::to_string(layout.ni) + " x " + std::to_string(layout.nj) + " traces has inline " +
                        std::to_string(layout.inline_of(i)) + ", crossline " + std::to_string(layout.crossline_of(j)),
                    {path},
                    "the traces are not a regular grid: sort them by inline then crossline and pad missing "
                    "traces before reading the file with geotandem");
}

class SegyVolume final : public Volume {
public:
  SegyVolume(std::string path, segy::Handle file, Layout layout, Geometry geometry)
      : path_(std::move(path)), file_(std::move(file)), layout_(layout), geometry_(std::move(geometry)) {}

  const Geometry& geometry() const override { return geometry_; }
  std::string format() const override { return "SEG-Y"; }
  std::string source() const override { return path_; }

protected:
  void read_box(const Box& box, std::span<float> out) const override {
    // segyio keeps a file position: one reader at a time per handle.
    std::lock_guard lock(mutex_);
    // Visit the traces in file order so that reads move forward through the file.
    if (layout_.inline_sorted) {
      for (std::int64_t i = box.lo[0]; i < box.hi[0]; ++i)
        for (std::int64_t j = box.lo[1]; j < box.hi[1]; ++j)
          read_trace(box, i, j, out.data() + box.offset({i, j, box.lo[2]}));
    } else {
      for (std::int64_t j = box.lo[1]; j < box.hi[1]; ++j)
        for (std::int64_t i = box.lo[0]; i < box.hi[0]; ++i)
          read_trace(box, i, j, out.data() + box.offset({i, j, box.lo[2]}));
    }
  }

private:
  void read_trace(const Box& box, std::int64_t i, std::int64_t j, float* out) const {
    const int trace = layout_.trace_of(i, j);
    check_position(read_header(file_.get(), layout_, trace, path_), layout_, i, j, trace, path_);
    const auto start = static_cast<int>(box.lo[2]), stop = static_cast<int>(box.hi[2]);
    int status = segy_readsubtr(file_.get(), trace, start, stop, 1, out, nullptr, layout_.trace0, layout_.trace_bytes);
    if (status != SEGY_OK)
      throw IoError("cannot read samples " + std::to_string(start) + " to " + std::to_string(stop) + " of trace " +
                        std::to_string(trace) + ": " + segy::status_text(status),
                    {path_, {}, {}, "box " + box.to_string(), {}});
    // segyio hands samples back big-endian and in the file's encoding (IBM or IEEE).
    segy_to_native(layout_.format, stop - start, out);
  }

  std::string path_;
  segy::Handle file_;
  Layout layout_;
  Geometry geometry_;
  mutable std::mutex mutex_;
};

// Reads the binary header and sizes: sample format, samples per trace, where traces start, how
// many there are. Refuses truncated files with the expected and actual sizes.
Layout read_layout(segy_file* file, const std::string& path) {
  std::array<char, SEGY_BINARY_HEADER_SIZE> bin{};
  if (int status = segy_binheader(file, bin.data()); status != SEGY_OK)
    throw FormatError("cannot read the 400-byte binary header after the 3200-byte textual header: " +
                          segy::status_text(status),
                      {path});
  Layout layout;
  layout.format = segy_format(bin.data());
  if (layout.format != SEGY_IBM_FLOAT_4_BYTE && layout.format != SEGY_IEEE_FLOAT_4_BYTE)
    throw FormatError("sample format code " + std::to_string(layout.format) + " (" + sample_format_name(layout.format) +
                          ", binary header byte 3225) is not supported",
                      {path},
                      "geotandem reads IBM float (1) and IEEE float (5) SEG-Y; convert the file to one of them");
  std::int32_t extended = 0;
  segy_get_bfield(bin.data(), SEGY_BIN_EXT_HEADERS, &extended);
  if (extended < 0)
    throw FormatError("a variable number of extended textual headers (binary header byte 3505 = " +
                          std::to_string(extended) + ") is not supported",
                      {path}, "rewrite the file with a fixed number of extended headers");
  layout.trace0 = segy_trace0(bin.data());

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
  // Intervals above 32767 are a negative number written as signed 16 bits (no survey samples that
  // slowly): refused, never read as 61.536 ms for -4000.
  if (interval >= 0x8000)
    throw FormatError("the sample interval is negative (" + std::to_string(interval - 0x10000) +
                          "; binary header bytes 3217-3218, or trace header bytes 117-118)",
                      {path}, "set a positive sample interval in microseconds");
  if (samples == 0)
    throw FormatError("no samples per trace: binary header byte 3221 and trace header byte 115 are both 0", {path});
  layout.trace_bytes = segy_trsize(layout.format, samples);

  std::error_code ec;
  const auto size = static_cast<long long>(std::filesystem::file_size(path, ec));
  const long long per_trace = layout.trace_bytes + SEGY_TRACE_HEADER_SIZE;
  if (size < layout.trace0 + per_trace)
    throw FormatError("the file has " + std::to_string(size) + " bytes, less than its headers (" +
                          std::to_string(layout.trace0) + " bytes) and one trace (" + std::to_string(per_trace) +
                          " bytes)",
                      {path}, "the file is truncated or not SEG-Y");
  int status = segy_traces(file, &layout.traces, layout.trace0, layout.trace_bytes);
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
  if (status != SEGY_OK) throw FormatError("cannot count the traces: " + segy::status_text(status), {path});
  return layout;
}

// Finds the sorting, the number of lines and their numbers; refuses pre-stack, unsorted and
// irregular files.
void read_lines(segy_file* file, const std::string& path, Layout& layout) {
  const int il = segy::kInlineField, xl = segy::kCrosslineField;
  int sorting = SEGY_UNKNOWN_SORTING;
  int status = segy_sorting(file, il, xl, segy::kOffsetField, &sorting, layout.trace0, layout.trace_bytes);
  if (status != SEGY_OK || sorting == SEGY_UNKNOWN_SORTING)
    throw FormatError("the traces are sorted neither by inline (byte 189) nor by crossline (byte 193)", {path},
                      "geotandem reads post-stack 3D cubes; sort the traces by inline then crossline, and check "
                      "that the line numbers are at bytes 189 and 193");
  layout.inline_sorted = sorting == SEGY_INLINE_SORTING;

  int offsets = 1;
  status = segy_offsets(file, il, xl, layout.traces, &offsets, layout.trace0, layout.trace_bytes);
  if (status != SEGY_OK || offsets != 1)
    throw FormatError("pre-stack data: " + std::to_string(offsets) +
                          " traces share each (inline, crossline) bin (offsets at byte 37)",
                      {path}, "geotandem needs a post-stack cube: stack the gathers or extract one offset first");

  int inlines = 0, crosslines = 0;
  status = segy_lines_count(file, il, xl, sorting, offsets, &inlines, &crosslines, layout.trace0, layout.trace_bytes);
  if (status != SEGY_OK || inlines < 1 || crosslines < 1 ||
      static_cast<long long>(inlines) * crosslines != layout.traces)
    throw FormatError("irregular survey: " + std::to_string(layout.traces) + " traces, but the first lines give " +
                          std::to_string(inlines) + " inlines x " + std::to_string(crosslines) +
                          " crosslines; traces are missing, lines differ in length, or the file was cut short",
                      {path},
                      "pad the cube to a full rectangle of traces, with dead traces where data is missing, before "
                      "reading it");
  layout.ni = inlines;
  layout.nj = crosslines;

  std::vector<int> il_numbers(static_cast<std::size_t>(inlines)), xl_numbers(static_cast<std::size_t>(crosslines));
  if (segy_inline_indices(file, il, sorting, inlines, crosslines, offsets, il_numbers.data(), layout.trace0,
                          layout.trace_bytes) != SEGY_OK ||
      segy_crossline_indices(file, xl, sorting, inlines, crosslines, offsets, xl_numbers.data(), layout.trace0,
                             layout.trace_bytes) != SEGY_OK)
    throw FormatError("cannot read the inline and crossline numbers", {path});
  auto regular_step = [&path](const std::vector<int>& numbers, const char* what) {
    int step = numbers.size() > 1 ? numbers[1] - numbers[0] : 1;
    for (std::size_t n = 1; n < numbers.size(); ++n)
      if (step == 0 || numbers[n] - numbers[n - 1] != step)
        throw FormatError(std::string(what) + " numbers are not evenly spaced: " + std::to_string(numbers[n - 1]) +
                              " then " + std::to_string(numbers[n]) + " after a step of " + std::to_string(step),
                          {path}, "geotandem needs a regular grid: pad the missing lines with dead traces");
    return step;
  };
  layout.il0 = il_numbers.front();
  layout.il_step = regular_step(il_numbers, "inline");
  layout.xl0 = xl_numbers.front();
  layout.xl_step = regular_step(xl_numbers, "crossline");
}

// CDP coordinates of a trace header, with the coordinate scalar of byte 71 applied.
std::array<double, 2> cdp_xy(const TraceHeader& header) {
  double scalar = field(header, SEGY_TR_SOURCE_GROUP_SCALAR);
  double factor = scalar == 0 ? 1.0 : scalar > 0 ? scalar : 1.0 / -scalar;
  return {field(header, SEGY_TR_CDP_X) * factor, field(header, SEGY_TR_CDP_Y) * factor};
}

// The affine from three corners: (0,0), (ni-1,0), (0,nj-1). A single line gives only one
// direction; the other is taken perpendicular with the same spacing (i east when j is north).
// Files without coordinates (all zero) get the default 25 m grid at the origin.
SurveyAffine fit_affine(const std::array<double, 2>& origin, const std::array<double, 2>& last_inline,
                        const std::array<double, 2>& last_crossline, int ni, int nj) {
  SurveyAffine a;
  a.x0 = origin[0];
  a.y0 = origin[1];
  if (ni > 1) {
    a.xi = (last_inline[0] - origin[0]) / (ni - 1);
    a.yi = (last_inline[1] - origin[1]) / (ni - 1);
  }
  if (nj > 1) {
    a.xj = (last_crossline[0] - origin[0]) / (nj - 1);
    a.yj = (last_crossline[1] - origin[1]) / (nj - 1);
  }
  if (ni == 1 && nj > 1) {
    a.xi = a.yj;
    a.yi = -a.xj;
  } else if (nj == 1 && ni > 1) {
    a.xj = -a.yi;
    a.yj = a.xi;
  }
  const double det = a.xi * a.yj - a.xj * a.yi;
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) {
    SurveyAffine fallback;
    fallback.x0 = a.x0;
    fallback.y0 = a.y0;
    return fallback;
  }
  return a;
}

// Our own textual header says when the sample axis is depth; other files are taken as time.
bool written_as_depth(segy_file* file) {
  std::array<char, SEGY_TEXT_HEADER_SIZE + 1> text{};
  if (segy_read_textheader(file, text.data()) != SEGY_OK) return false;
  std::string header(text.data(), SEGY_TEXT_HEADER_SIZE);
  return header.substr(0, 80).find(segy::kMark) != std::string::npos &&
         header.find(segy::kDepthMark) != std::string::npos;
}

} // namespace

std::unique_ptr<Volume> open_segy(const std::string& path, const OpenOptions&) {
  segy::Handle file(segy_open(path.c_str(), "rb"));
  if (!file)
    throw IoError(std::string("cannot open the SEG-Y file: ") + std::strerror(errno), {path}, "check its permissions");
  Layout layout = read_layout(file.get(), path);
  // Tells segyio the sample size for sub-trace reads (4 bytes for both supported formats).
  segy_set_format(file.get(), layout.format);
  // Memory-map the file when the system allows: a box of short sub-traces then costs memory
  // copies instead of two seeks and reads per trace (64^3 blocks read ~5x faster). The hazard:
  // a file truncated by another process while mapped raises SIGBUS on access. When mapping fails
  // segyio keeps using stdio.
  segy_mmap(file.get());
  read_lines(file.get(), path, layout);

  // The corners fix the affine; checking their line numbers also catches most irregular files
  // at open time rather than at the first read.
  const int ni = layout.ni, nj = layout.nj;
  auto corner = [&](int i, int j) {
    const int trace = layout.trace_of(i, j);
    TraceHeader header = read_header(file.get(), layout, trace, path);
    check_position(header, layout, i, j, trace, path);
    return header;
  };
  const TraceHeader origin = corner(0, 0);
  const TraceHeader last_inline = corner(ni - 1, 0);
  const TraceHeader last_crossline = corner(0, nj - 1);
  corner(ni - 1, nj - 1);

  if (layout.interval == 0)
    throw FormatError("no sample interval: binary header byte 3217 and trace header byte 117 are both 0", {path},
                      "set the sample interval (microseconds) in the binary header");
  const bool depth = written_as_depth(file.get());
  Geometry g;
  g.shape = {ni, nj, layout.samples};
  g.inline0 = layout.il0;
  g.inline_step = layout.il_step;
  g.crossline0 = layout.xl0;
  g.crossline_step = layout.xl_step;
  g.z_unit = depth ? SampleUnit::metres : SampleUnit::milliseconds;
  g.dz = layout.interval / 1000.0; // microseconds to ms (or, in our depth files, mm to m)
  // Delay recording time (byte 109), scaled by byte 215 when that is set (rev 1).
  const double time_scalar = field(origin, SEGY_TR_SCALAR_TRACE_HEADER);
  const double delay = field(origin, SEGY_TR_DELAY_REC_TIME);
  g.z0 = time_scalar == 0 ? delay : time_scalar > 0 ? delay * time_scalar : delay / -time_scalar;
  g.affine = fit_affine(cdp_xy(origin), cdp_xy(last_inline), cdp_xy(last_crossline), ni, nj);
  return std::make_unique<SegyVolume>(path, std::move(file), layout, g);
}

} // namespace geotandem::volume::detail
