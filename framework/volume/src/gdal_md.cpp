// Reader of cubes stored as 3-D arrays in netCDF-4, HDF5 and Zarr, through GDAL's multidimensional
// API. The writer is in gdal_md_write.cpp; array choice and geometry in gdal_md_inspect.cpp.

#include <algorithm>
#include <array>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "formats.hpp"
#include "gdal_common.hpp"
#include "gdal_md_chunks.hpp"
#include "gdal_md_inspect.hpp"
#include "gdal_module.hpp"
#include "geotandem/core/error.hpp"
#include "raw_sidecar.hpp"

namespace geotandem::volume::detail {
namespace {

const char* driver_of(Format format) {
  switch (format) {
  case Format::netcdf: return "netCDF";
  case Format::hdf5: return "HDF5";
  case Format::zarr: return "Zarr";
  default: return nullptr;
  }
}

// Reads boxes as hyperslabs of one array. Owns its dataset: GDAL datasets are not thread-safe, so
// use one GdalMdVolume per thread.
class GdalMdVolume final : public Volume {
public:
  GdalMdVolume(std::string path, std::string format, gdal::DatasetPtr dataset, std::shared_ptr<GDALGroup> root,
               std::shared_ptr<GDALMDArray> array, std::string array_name, Geometry geometry,
               std::optional<float> no_data, gdal::LineGaps gaps, ChunkLayout chunks)
      : path_(std::move(path)), format_(std::move(format)), dataset_(std::move(dataset)), root_(std::move(root)),
        array_(std::move(array)), array_name_(std::move(array_name)), geometry_(std::move(geometry)), no_data_(no_data),
        gaps_(std::move(gaps)), chunks_(std::move(chunks)) {
    // stored_[a][g]: the stored line at cube index g, -1 where the survey has none.
    for (std::size_t a = 0; a < 2; ++a) {
      if (gaps_.grid[a].empty()) continue;
      stored_[a].assign(static_cast<std::size_t>(geometry_.shape[static_cast<int>(a)]), -1);
      for (std::size_t m = 0; m < gaps_.grid[a].size(); ++m)
        stored_[a][static_cast<std::size_t>(gaps_.grid[a][m])] = static_cast<std::int64_t>(m);
    }
  }

  ~GdalMdVolume() override {
    // Arrays and groups first: some drivers keep the file open while any handle lives.
    gdal::ErrorCapture quiet;
    array_.reset();
    root_.reset();
    dataset_.reset();
  }

  const Geometry& geometry() const override { return geometry_; }
  std::string format() const override { return format_; }
  std::string source() const override { return path_; }
  std::vector<FormatDetail> format_details() const override {
    std::vector<FormatDetail> details{{"array", array_name_}}; // which of the file's arrays is read
    if (!chunks_.text.empty()) details.push_back({"chunks", chunks_.text});
    if (chunks_.reads_per_chunk >= kSlowReads) {
      const double copy_bytes = copy_slabs(chunks_, geometry_.shape).axis >= 0
                                    ? static_cast<double>(geometry_.sample_count()) * sizeof(float)
                                    : 0.0;
      details.push_back({"slow_reads", slow_reads_text(chunks_, format_, copy_bytes)});
    }
    if (no_data_) details.push_back(gdal::no_data_detail(*no_data_));
    if (gaps_.any()) {
      const char* axis[2] = {"inlines ", "crosslines "};
      std::string text;
      for (std::size_t a = 0; a < 2; ++a)
        if (!gaps_.missing[a].empty()) text += (text.empty() ? "" : "; ") + (axis[a] + gaps_.missing[a]);
      details.push_back({"missing_lines", text + ", read as missing samples"});
    }
    return details;
  }
  std::optional<float> declared_no_data() const override { return no_data_; }
  std::string reopen_hint() const override { return copy_ ? kCopyHint + copy_path_ : std::string(); }

  std::string use_block_copy(const std::string& directory, Progress* progress,
                             const CancelToken& cancel) const override {
    if (copy_) return copy_path_;
    const CopySlabs slabs = copy_slabs(chunks_, geometry_.shape);
    if (slabs.axis < 0) return {};
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(directory, ec);
    if (ec)
      throw IoError("cannot make the directory for a copy of the input: " + ec.message(), {directory},
                    "check that the output directory is writable");
    // Absolute: workers started elsewhere (a cluster job's directory) find it by this name.
    const fs::path where = fs::absolute(directory);
    const std::string path = (where / copy_name(path_, array_name_)).string();
    bool taken = false;
    try {
      taken = take_copy(path);
    } catch (const Error&) {
      // A damaged copy of this very file: written again below.
    }
    if (!taken) {
      // Not to fill the disk on the way to failing: the copy needs the whole cube, and a little room
      // is left for the run's own output.
      const std::uintmax_t bytes = geometry_.sample_count() * sizeof(float);
      const fs::space_info space = fs::space(where, ec);
      if (!ec && space.available < bytes + bytes / 16)
        throw IoError("not enough free space for a copy of the input: it needs " + std::to_string(bytes >> 20) +
                          " MiB, " + std::to_string(space.available >> 20) + " MiB are free",
                      {directory}, "free some space, or rewrite the file in chunks of about 64 samples an axis");
      // A damaged copy's sidecar goes first: until the new one appears, nobody takes the half-written copy.
      fs::remove(raw_sidecar_of(path), ec);
      NullProgress quiet;
      write_raw_slabs(*this, path, slabs.axis, slabs.thickness,
                      "copying " + fs::path(path_).filename().string() + " for block reads",
                      progress ? *progress : quiet, cancel);
      if (!take_copy(path)) throw IoError("the copy of the input just written cannot be read", {path});
    }
    return copy_path_;
  }

  // Reads the copy another process made (OpenOptions::reopen_hint) when it is the copy of this
  // file as it is now; otherwise the file is read.
  void take_hint(const std::string& hint) const {
    if (hint.rfind(kCopyHint, 0) != 0) return;
    const std::string path = hint.substr(std::char_traits<char>::length(kCopyHint));
    if (std::filesystem::path(path).filename() != copy_name(path_, array_name_)) return;
    try {
      take_copy(path);
    } catch (const Error&) {
      // Gone or damaged: the file itself still reads.
    }
  }

protected:
  void read_box(const Box& box, std::span<float> out) const override {
    if (copy_) {
      copy_->read(box, out);
      return;
    }
    if (!gaps_.any()) {
      read_stored(box, box.lo, out.data(), box);
      return;
    }
    // A survey with missing lines: NaN everywhere, then every block of stored lines that are
    // neighbours in both the file and the cube read in one piece into its place.
    std::fill(out.begin(), out.end(), std::numeric_limits<float>::quiet_NaN());
    const auto runs0 = runs(0, box.lo[0], box.hi[0]), runs1 = runs(1, box.lo[1], box.hi[1]);
    for (const Run& r0 : runs0)
      for (const Run& r1 : runs1) {
        const Box part{{r0.lo, r1.lo, box.lo[2]}, {r0.hi, r1.hi, box.hi[2]}};
        std::vector<float> stored(static_cast<std::size_t>(part.count()));
        read_stored(part, {r0.stored, r1.stored, box.lo[2]}, stored.data(), box);
        copy_region(stored.data(), part, out.data(), box, part);
      }
  }

private:
  // Reads from the raw copy at `path` when it is complete (its sidecar is written last) and holds
  // this cube's shape; false when there is none. Throws what opening a damaged copy throws.
  bool take_copy(const std::string& path) const {
    if (!std::filesystem::exists(raw_sidecar_of(path))) return false;
    auto copy = open_raw(path, {});
    if (copy->geometry().shape != geometry_.shape) return false;
    copy_ = std::move(copy);
    copy_path_ = path;
    return true;
  }

  // Cube indices [lo, hi) along an axis held by stored lines stored .. stored + (hi - lo).
  struct Run {
    std::int64_t lo, hi, stored;
  };
  std::vector<Run> runs(std::size_t axis, std::int64_t lo, std::int64_t hi) const {
    std::vector<Run> out;
    for (auto g = lo; g < hi; ++g) {
      const std::int64_t s = stored_[axis].empty() ? g : stored_[axis][static_cast<std::size_t>(g)];
      if (s < 0) continue;
      if (!out.empty() && out.back().hi == g && out.back().stored + (g - out.back().lo) == s)
        ++out.back().hi;
      else
        out.push_back({g, g + 1, s});
    }
    return out;
  }

  // Reads the stored hyperslab starting at `stored` with the extent of `part` into `out`, in C order.
  void read_stored(const Box& part, const Index3& stored, float* out, const Box& asked) const {
    gdal::ErrorCapture errors;
    std::array<GUInt64, 3> start{};
    std::array<std::size_t, 3> count{};
    for (int a = 0; a < 3; ++a) {
      start[static_cast<std::size_t>(a)] = static_cast<GUInt64>(stored[a]);
      count[static_cast<std::size_t>(a)] = static_cast<std::size_t>(part.size(a));
    }
    // Null steps and strides: a contiguous C-order buffer of exactly the box, which is our layout.
    const std::size_t bytes = static_cast<std::size_t>(part.count()) * sizeof(float);
    if (!array_->Read(start.data(), count.data(), nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float32), out, out,
                      bytes)) {
      std::string what = "cannot read the samples of array " + array_->GetFullName() + errors.text();
      ErrorContext where{path_, {}, {}, "box " + asked.to_string(), {}};
      if (errors.first_error() == CPLE_FileIO || errors.first_error() == CPLE_OpenFailed)
        throw IoError(what, where, "check that the file is still there and readable");
      throw FormatError(what, where, "the file may be truncated or damaged");
    }
  }

  std::string path_;
  std::string format_;
  // Declaration order matters: destroyed in reverse, the array before the dataset.
  gdal::DatasetPtr dataset_;
  std::shared_ptr<GDALGroup> root_;
  std::shared_ptr<GDALMDArray> array_;
  std::string array_name_; // the stored array's full name, "/chaos"
  Geometry geometry_;
  std::optional<float> no_data_; // the array's _FillValue, missing_value or fill_value
  gdal::LineGaps gaps_;
  ChunkLayout chunks_;
  std::array<std::vector<std::int64_t>, 2> stored_;
  // The raw copy that reads go to once use_block_copy made or found it (or a hint named it).
  mutable std::unique_ptr<Volume> copy_;
  mutable std::string copy_path_;
};

// What the file really is, from the driver that opened it ("netCDF-4" for the netCDF driver, which
// also reads classic netCDF).
std::string format_of(GDALDataset& dataset, Format format) {
  GDALDriver* driver = dataset.GetDriver();
  const std::string name = driver ? driver->GetDescription() : "";
  if (name == "HDF5") return format_name(Format::hdf5);
  if (name == "Zarr") return format_name(Format::zarr);
  if (name == "netCDF") return format_name(Format::netcdf);
  if (name == "MEM") return "MEM";
  return format_name(format);
}

} // namespace

namespace {

std::unique_ptr<Volume> volume_of(gdal::DatasetPtr dataset, const std::string& path, Format format,
                                  const OpenOptions& options) {
  gdal::ErrorCapture errors;
  std::shared_ptr<GDALGroup> root = dataset->GetRootGroup();
  if (!root)
    throw FormatError("the file has no root group" + errors.text(), {path},
                      "the file may be truncated or damaged; check that it was written completely");
  std::shared_ptr<GDALMDArray> stored = gdal::choose_array(*root, options.variable, path);
  std::shared_ptr<GDALMDArray> cube = gdal::in_cube_order(stored, path);
  gdal::LineGaps gaps;
  Geometry geometry = gdal::read_geometry(*cube, *stored, path, options.nan_policy == NanPolicy::fill, &gaps);
  try {
    if (auto crs = gdal::read_crs(*root, *stored, path)) geometry.crs = *crs;
  } catch (const FormatError&) {
    // A user's CRS (applied by open_volume) replaces the file's: what OSR cannot read there then
    // does not matter.
    if (!options.crs) throw;
  }
  std::string name = format_of(*dataset, format);
  bool declared = false;
  const double no_data = stored->GetNoDataValueAsDouble(&declared);
  std::string array_name = stored->GetFullName();
  ChunkLayout chunks = chunk_layout(*stored, *cube);
  stored.reset();
  auto volume = std::make_unique<GdalMdVolume>(path, std::move(name), std::move(dataset), std::move(root),
                                               std::move(cube), std::move(array_name), std::move(geometry),
                                               gdal::no_data_of(declared, no_data), std::move(gaps), std::move(chunks));
  if (!options.reopen_hint.empty()) volume->take_hint(options.reopen_hint);
  return volume;
}

} // namespace

std::unique_ptr<Volume> gdal::open_md(const std::string& path, Format format, const OpenOptions& options) {
  const char* driver = driver_of(format);
  if (!driver) throw InvalidArgument(std::string("not a multidimensional format: ") + format_name(format), {path});
  return volume_of(gdal::open_dataset(path, GDAL_OF_MULTIDIM_RASTER, driver, format_name(format)), path, format,
                   options);
}

std::unique_ptr<Volume> gdal::open_md_dataset(GDALDataset* dataset, const std::string& name,
                                              const OpenOptions& options) {
  gdal::DatasetPtr owned(dataset);
  if (!owned) throw InvalidArgument("no GDAL dataset given", {name});
  return volume_of(std::move(owned), name, Format::netcdf, options);
}

} // namespace geotandem::volume::detail
