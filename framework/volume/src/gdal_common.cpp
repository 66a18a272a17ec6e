#include "gdal_common.hpp"

#include <dlfcn.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "geotandem/core/error.hpp"
#include "geotandem/core/params.hpp"

namespace geotandem::volume::detail::gdal {

void register_drivers() {
  // A function-local static is initialised once, thread-safely; GDALAllRegister is idempotent
  // but walks every driver, so it is worth skipping on later calls.
  static const bool registered = [] {
    GDALAllRegister();
    return true;
  }();
  (void)registered;
}

namespace {

// HDF5 (under netCDF-4 and HDF5 files) prints its error stack to stderr unless told not to, and
// in Debian's thread-safe build that setting belongs to each thread: netCDF turns it off only in
// the thread that initialised it, so harmless probes (netCDF looking for optional attributes)
// flood stderr from every other thread. Each thread that reaches GDAL through us turns it off for
// itself. HDF5 is found at run time (GDAL's drivers load it) so that we need not link it: the
// call is H5Eset_auto2(H5E_DEFAULT = 0, no printer, no data); hid_t is int64_t since HDF5 1.10.
void silence_hdf5_in_this_thread() {
  thread_local bool done = false;
  if (done) return;
  done = true;
  using SetAuto = int (*)(std::int64_t, void*, void*);
  if (void* symbol = dlsym(RTLD_DEFAULT, "H5Eset_auto2")) reinterpret_cast<SetAuto>(symbol)(0, nullptr, nullptr);
}

} // namespace

ErrorCapture::ErrorCapture() {
  silence_hdf5_in_this_thread();
  CPLPushErrorHandlerEx(&ErrorCapture::handle, this);
}

ErrorCapture::~ErrorCapture() {
  CPLPopErrorHandler();
}

void CPL_STDCALL ErrorCapture::handle(CPLErr level, CPLErrorNum number, const char* message) {
  auto* self = static_cast<ErrorCapture*>(CPLGetErrorHandlerUserData());
  if (!self || level == CE_None || level == CE_Debug) return;
  if (level == CE_Failure || level == CE_Fatal) {
    if (!self->failed_) self->first_error_ = number;
    self->failed_ = true;
  }
  // Keep the first few: a broken file can make GDAL repeat itself for every chunk.
  if (self->messages_.size() < 4 && message) self->messages_.emplace_back(message);
}

std::string ErrorCapture::text() const {
  if (messages_.empty()) return {};
  std::string out = "; GDAL: ";
  for (std::size_t n = 0; n < messages_.size(); ++n)
    out += (n ? "; " : "") + messages_[n];
  return out;
}

void ErrorCapture::clear() {
  messages_.clear();
  failed_ = false;
  first_error_ = CPLE_None;
}

void DatasetCloser::operator()(GDALDataset* dataset) const {
  if (dataset) GDALClose(GDALDataset::ToHandle(dataset));
}

DatasetPtr open_dataset(const std::string& path, unsigned flags, const char* driver, const std::string& format) {
  register_drivers();
  ErrorCapture errors;
  const char* const drivers[] = {driver, nullptr};
  GDALDatasetH handle =
      GDALOpenEx(path.c_str(), flags | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR, drivers, nullptr, nullptr);
  if (!handle)
    throw FormatError("cannot open the file as " + format + errors.text(), {path},
                      "the file may be truncated or damaged; check that it was written completely");
  return DatasetPtr(GDALDataset::FromHandle(handle));
}

void close_written(DatasetPtr dataset, const std::string& path) {
  ErrorCapture errors;
  dataset.reset();
  if (errors.failed())
    throw IoError("writing failed while flushing the file" + errors.text(), {path},
                  "check free disk space and write permission");
}

namespace {

constexpr std::array<GeometryField, 12> fields{{
    {"geotandem_inline0", [](Geometry& g) -> double& { return g.inline0; }},
    {"geotandem_inline_step", [](Geometry& g) -> double& { return g.inline_step; }},
    {"geotandem_crossline0", [](Geometry& g) -> double& { return g.crossline0; }},
    {"geotandem_crossline_step", [](Geometry& g) -> double& { return g.crossline_step; }},
    {"geotandem_z0", [](Geometry& g) -> double& { return g.z0; }},
    {"geotandem_dz", [](Geometry& g) -> double& { return g.dz; }},
    {"geotandem_x0", [](Geometry& g) -> double& { return g.affine.x0; }},
    {"geotandem_xi", [](Geometry& g) -> double& { return g.affine.xi; }},
    {"geotandem_xj", [](Geometry& g) -> double& { return g.affine.xj; }},
    {"geotandem_y0", [](Geometry& g) -> double& { return g.affine.y0; }},
    {"geotandem_yi", [](Geometry& g) -> double& { return g.affine.yi; }},
    {"geotandem_yj", [](Geometry& g) -> double& { return g.affine.yj; }},
}};

} // namespace

std::span<const GeometryField> geometry_fields() {
  return fields;
}

double field_value(const Geometry& geometry, const GeometryField& field) {
  Geometry copy = geometry;
  return field.field(copy);
}

std::string format_double(double value) {
  std::array<char, 64> text{};
  std::snprintf(text.data(), text.size(), "%.17g", value);
  return text.data();
}

std::optional<double> parse_double(const char* text) {
  if (!text || !*text) return std::nullopt;
  char* end = nullptr;
  double value = std::strtod(text, &end);
  while (end && (*end == ' ' || *end == '\t'))
    ++end;
  if (!end || *end != '\0' || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::string type_name(GDALDataType type) {
  const char* name = GDALGetDataTypeName(type);
  return name ? name : "unknown type";
}

void stream_boxes(const Volume& source, const Index3& block, const std::string& label, Progress& progress,
                  const CancelToken& cancel, const std::function<void(const Box&, std::span<const float>)>& write) {
  const Index3 shape = source.geometry().shape;
  Index3 counts{};
  for (int a = 0; a < 3; ++a)
    counts[a] = (shape[a] + block[a] - 1) / block[a];
  progress.begin(label, static_cast<std::uint64_t>(counts[0] * counts[1] * counts[2]), "blocks");
  std::vector<float> buffer;
  std::uint64_t done = 0;
  for (std::int64_t bi = 0; bi < counts[0]; ++bi)
    for (std::int64_t bj = 0; bj < counts[1]; ++bj)
      for (std::int64_t bk = 0; bk < counts[2]; ++bk) {
        cancel.throw_if_cancelled();
        Box box{{bi * block[0], bj * block[1], bk * block[2]},
                {(bi + 1) * block[0], (bj + 1) * block[1], (bk + 1) * block[2]}};
        box = box.intersection(Box::of_shape(shape));
        buffer.resize(box.count());
        source.read(box, buffer);
        write(box, buffer);
        progress.update(++done);
      }
  progress.end();
}

std::optional<float> no_data_of(bool declared, double value) {
  if (!declared || std::isnan(value)) return std::nullopt;
  return static_cast<float>(value); // beyond float range: infinite, as the float samples then are
}

FormatDetail no_data_detail(float no_data) {
  return {kNoDataDetail, number_text(no_data) + " (samples equal to it are missing: see --nan)"};
}

} // namespace geotandem::volume::detail::gdal
