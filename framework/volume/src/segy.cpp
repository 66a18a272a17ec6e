// SEG-Y reader: a post-stack 3D cube, inline- or crossline-sorted, in sample formats 1 (IBM
// float), 2 (32-bit integer), 3 (16-bit integer), 5 (IEEE float) or 8 (8-bit integer), big- or
// little-endian, read trace by trace through segyio. Opening reads the headers only; read_box
// reads the traces of the box and nothing else. The binary header is read in segy_layout.cpp, the
// grid of line numbers in segy_grid.cpp.

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <mutex>
#include <vector>

#include "formats.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/core/params.hpp"
#include "segy_coordinates.hpp"
#include "segy_file.hpp"
#include "segy_grid.hpp"
#include "segy_grid_hint.hpp"
#include "segy_header.hpp"
#include "segy_layout.hpp"

namespace geotandem::volume::detail {
namespace {

using segy::Grid;
using segy::Layout;
using segy::TraceHeader;

// Integer samples become floats without scaling, as segyio hands them back (the trace header's
// gain fields are almost never set in post-stack cubes).
template <class Int> void widen(const char* native, int count, float* out) {
  for (int n = 0; n < count; ++n) {
    Int value;
    std::memcpy(&value, native + static_cast<std::size_t>(n) * sizeof(Int), sizeof(Int));
    out[n] = static_cast<float>(value);
  }
}

// Trace identification code (bytes 29-30) of a dead trace.
constexpr int kDeadTrace = 2;

// The time (or depth) of a trace's first sample: the delay recording time (byte 109), scaled by
// byte 215 when that is set (rev 1).
double trace_start(const TraceHeader& header) {
  const double scalar = segy::field(header, SEGY_TR_SCALAR_TRACE_HEADER);
  const double delay = segy::field(header, SEGY_TR_DELAY_REC_TIME);
  return scalar == 0 ? delay : scalar > 0 ? delay * scalar : delay / -scalar;
}

class SegyVolume final : public Volume {
public:
  // `coordinates`: how geographic trace coordinates were taken (TraceCoordinates::description);
  // empty for lengths.
  // `stamp`: the file's when it was opened, which the grid handed to other processes carries.
  // `where`: where the coordinates were read and how they were scaled (TraceCoordinates::where).
  SegyVolume(std::string path, segy::Handle file, segy::HeaderFile headers, Layout layout, Grid grid, Geometry geometry,
             std::string coordinates, std::string where, segy::FileStamp stamp)
      : path_(std::move(path)), file_(std::move(file)), headers_(std::move(headers)), layout_(layout),
        grid_(std::move(grid)), geometry_(std::move(geometry)), coordinates_(std::move(coordinates)),
        where_(std::move(where)), stamp_(stamp) {}

  const Geometry& geometry() const override { return geometry_; }
  std::string format() const override { return "SEG-Y"; }
  std::string source() const override { return path_; }
  // Made when asked (by a manager, for its workers), not at every open.
  std::string reopen_hint() const override { return segy::grid_hint(grid_, stamp_); }
  std::vector<FormatDetail> format_details() const override {
    std::vector<FormatDetail> details{{"sample_format", std::string(segy::sample_format_name(layout_.format)) +
                                                            " (code " + std::to_string(layout_.format) + ")"},
                                      {"byte_order", segy::byte_order_name(layout_.little_endian)},
                                      {"revision", revision_text()},
                                      {"inline_byte", std::to_string(grid_.bytes.inline_byte)},
                                      {"crossline_byte", std::to_string(grid_.bytes.crossline_byte)},
                                      {"inline_type", to_string(grid_.bytes.inline_type)},
                                      {"crossline_type", to_string(grid_.bytes.crossline_type)},
                                      {"coordinate_fields", where_},
                                      {"sorting", sorting_text()},
                                      {"traces", traces_text()}};
    if (!coordinates_.empty()) details.push_back({"coordinates", coordinates_});
    const int m = layout_.measurement_system;
    const std::string bytes = " (binary header bytes 3255-3256 = " + std::to_string(m) + ")";
    details.push_back({"measurement", (m == 1 ? "metres" : m == 2 ? "feet" : "not given") + bytes});
    // Without a CRS x and y are taken as metres (volume::Crs); the file says otherwise. The
    // warning goes when a CRS is given (volume::with_crs drops it): its unit is the one used.
    if (m == 2 && geometry_.crs.empty())
      details.push_back({"units_warning", "the binary header says feet" + bytes +
                                              ", but without a CRS x, y and volumes are labelled in metres: give "
                                              "the survey's CRS in feet (--crs, input.crs) to have them in feet"});
    return details;
  }

protected:
  std::string revision_text() const {
    std::string text = layout_.revision_text() + " (binary header bytes 3501-3502)";
    if (layout_.extended_textual > 0)
      text += "; " + std::to_string(layout_.extended_textual) + " extended textual headers (byte 3505)";
    if (layout_.header_extensions > 0)
      text += "; " + std::to_string(layout_.header_extensions) +
              " trace header extensions of 240 bytes per trace (bytes 3507-3510)";
    return text;
  }
  std::string sorting_text() const {
    if (grid_.unsorted)
      return "unsorted: read through a trace index of " + std::to_string(grid_.traces.size()) +
             " bins built from every trace header (4 bytes per bin)";
    std::string text = grid_.sorting();
    if (grid_.irregular()) text += ", read through a trace index built from every trace header";
    return text;
  }
  std::string traces_text() const {
    if (grid_.missing_bins())
      return "an irregular survey, whose missing traces read as missing samples: " + segy::missing_text(grid_);
    std::string text = std::to_string(grid_.ni * grid_.nj) + ", every bin of the grid";
    if (grid_.placeholders_left_out > 0)
      text += "; " + std::to_string(grid_.placeholders_left_out) +
              " placeholders (dead traces with line numbers 0) besides them, not read";
    return text;
  }

  void read_box(const Box& box, std::span<float> out) const override {
    // segyio keeps a file position: one reader at a time per handle.
    std::lock_guard lock(mutex_);
    // Visit the traces in file order so that reads move forward through the file.
    if (grid_.inline_sorted) {
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
    const int trace = grid_.trace_of(i, j);
    if (trace < 0) { // a bin of an irregular survey without a trace: missing samples
      std::fill_n(out, box.size(2), std::numeric_limits<float>::quiet_NaN());
      return;
    }
    const TraceHeader header = headers_.read(trace);
    segy::check_position(header, grid_, i, j, trace, path_);
    // A dead trace (identification code 2) holds no signal: where its zeros start does not matter.
    if (const double start = trace_start(header);
        start != geometry_.z0 && segy::field(header, SEGY_TR_TRACE_ID) != kDeadTrace)
      throw FormatError("trace " + std::to_string(trace) + " (inline " + std::to_string(grid_.inline_of(i)) +
                            ", crossline " + std::to_string(grid_.crossline_of(j)) + ") starts at " +
                            number_text(start) + " where the cube's first trace starts at " +
                            number_text(geometry_.z0) + " (delay recording time, trace header bytes 109-110)",
                        {path_, {}, {}, "box " + box.to_string(), {}},
                        "geotandem reads cubes whose traces all start at the same time or depth; pad or shift the "
                        "traces to a common start first");
    const auto start = static_cast<int>(box.lo[2]), stop = static_cast<int>(box.hi[2]);
    const int count = stop - start;
    // 4-byte samples are decoded in place; narrower integers go through a scratch buffer.
    const bool in_place = layout_.sample_size() == 4;
    if (!in_place) scratch_.resize(static_cast<std::size_t>(count) * static_cast<std::size_t>(layout_.sample_size()));
    void* raw = in_place ? static_cast<void*>(out) : static_cast<void*>(scratch_.data());
    int status = segy_readsubtr(file_.get(), trace, start, stop, 1, raw, nullptr, layout_.segyio_trace0(),
                                layout_.segyio_trace_bytes());
    if (status != SEGY_OK)
      throw IoError("cannot read samples " + std::to_string(start) + " to " + std::to_string(stop) + " of trace " +
                        std::to_string(trace) + ": " + segy::status_text(status),
                    {path_, {}, {}, "box " + box.to_string(), {}});
    // segyio hands samples back big-endian and in the file's encoding; segy_to_native makes them
    // native floats (IBM, IEEE) or native integers.
    segy_to_native(layout_.format, count, raw);
    switch (layout_.format) {
    case SEGY_SIGNED_INTEGER_4_BYTE: widen<std::int32_t>(reinterpret_cast<const char*>(out), count, out); break;
    case SEGY_SIGNED_SHORT_2_BYTE: widen<std::int16_t>(scratch_.data(), count, out); break;
    case SEGY_SIGNED_CHAR_1_BYTE: widen<std::int8_t>(scratch_.data(), count, out); break;
    default: break;
    }
  }

  std::string path_;
  segy::Handle file_;
  segy::HeaderFile headers_;
  Layout layout_;
  Grid grid_;
  Geometry geometry_;
  std::string coordinates_;
  std::string where_;
  segy::FileStamp stamp_;
  mutable std::mutex mutex_;
  mutable std::vector<char> scratch_; // guarded by mutex_
};

// `a` when it maps the grid onto a plane; otherwise (collinear or missing coordinates) the default
// 25 m grid at a's origin.
SurveyAffine usable_or_default(const SurveyAffine& a) {
  const double det = a.xi * a.yj - a.xj * a.yi;
  if (std::abs(det) > 0.0 && std::isfinite(det)) return a;
  SurveyAffine fallback;
  fallback.x0 = a.x0;
  fallback.y0 = a.y0;
  return fallback;
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
  return usable_or_default(a);
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

std::unique_ptr<Volume> open_segy(const std::string& path, const OpenOptions& options) {
  segy::Handle file(segy_open(path.c_str(), "rb"));
  if (!file)
    throw IoError(std::string("cannot open the SEG-Y file: ") + std::strerror(errno), {path}, "check its permissions");
  // Detects the byte order and tells segyio the sample format (segy_set_format).
  Layout layout = segy::read_layout(file.get(), path);
  check_segy_options(options.segy, path);
  const segy::HeaderFile headers(path, layout);
  // Memory-map the file when the system allows: a box of short sub-traces then costs memory
  // copies instead of two seeks and reads per trace (64^3 blocks read ~5x faster). The hazard:
  // a file truncated by another process while mapped raises SIGBUS on access. When mapping fails
  // segyio keeps using stdio.
  segy_mmap(file.get());
  // An irregular survey's grid costs a pass over every trace header; a process given the grid by
  // the one that made that pass (the manager, for its workers) skips it while the file is unchanged.
  const bool read_missing = options.nan_policy == NanPolicy::fill;
  const segy::FileStamp stamp = segy::file_stamp(path);
  std::optional<Grid> hinted;
  if (!options.reopen_hint.empty()) {
    hinted = segy::grid_from_hint(options.reopen_hint, stamp, options.segy, layout.traces);
    // Missing traces are refused unless read as missing samples: find_grid refuses them, naming them.
    if (hinted && !read_missing && hinted->missing_bins()) hinted.reset();
  }
  Grid grid = hinted ? std::move(*hinted)
                     : segy::find_grid(headers, layout, options.segy, read_missing, path, options.progress);

  const int ni = grid.ni, nj = grid.nj;
  auto corner = [&](int i, int j) { return headers.read(grid.trace_of(i, j)); };
  // The first live trace of the file (not a placeholder) gives the sample axis. A grid found from a
  // few headers has its affine fixed by its corners (find_grid checked their line numbers); one
  // found by reading every header (irregular, or padded with placeholders) had it fitted to every
  // live trace, as they were read.
  const int origin_trace = grid.fitted ? grid.first_live : grid.trace_of(0, 0);
  const TraceHeader origin = headers.read(origin_trace);

  if (layout.interval == 0)
    throw FormatError("no sample interval: binary header byte 3217 and trace header byte 117 are both 0", {path},
                      "set the sample interval (microseconds) in the binary header");
  const bool depth = written_as_depth(file.get());
  Geometry g;
  g.shape = {ni, nj, layout.samples};
  g.inline0 = grid.il0;
  g.inline_step = grid.il_step;
  g.crossline0 = grid.xl0;
  g.crossline_step = grid.xl_step;
  g.z_unit = depth ? SampleUnit::metres : SampleUnit::milliseconds;
  g.dz = layout.interval / 1000.0; // microseconds to ms (or, in our depth files, mm to m)
  g.z0 = trace_start(origin);
  // Both the scan and this take the file's first live trace (the corner (0, 0) of a grid found from
  // its corners) as the reference of geographic coordinates.
  const segy::TraceCoordinates coordinates(origin, options.segy, origin_trace, path);
  const auto xy_at = [&](int i, int j) { return coordinates.xy(corner(i, j), grid.trace_of(i, j), path); };
  g.affine = grid.fitted
                 ? usable_or_default(grid.fitted_affine)
                 : fit_affine(coordinates.xy(origin, origin_trace, path), xy_at(ni - 1, 0), xy_at(0, nj - 1), ni, nj);
  return std::make_unique<SegyVolume>(path, std::move(file), headers, layout, std::move(grid), g,
                                      coordinates.description(), coordinates.where(), stamp);
}

} // namespace geotandem::volume::detail
