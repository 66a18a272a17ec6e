// Reader of cubes stored as 3-D arrays in netCDF-4, HDF5 and Zarr, through GDAL's multidimensional
// API. The writer is in gdal_md_write.cpp; array choice and geometry in gdal_md_inspect.cpp.

#include <array>
#include <optional>

#include "formats.hpp"
#include "gdal_common.hpp"
#include "gdal_md_inspect.hpp"
#include "gdal_module.hpp"
#include "geotandem/core/error.hpp"

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
               std::optional<float> no_data)
      : path_(std::move(path)), format_(std::move(format)), dataset_(std::move(dataset)), root_(std::move(root)),
        array_(std::move(array)), array_name_(std::move(array_name)), geometry_(std::move(geometry)),
        no_data_(no_data) {}

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
    if (no_data_) details.push_back(gdal::no_data_detail(*no_data_));
    return details;
  }
  std::optional<float> declared_no_data() const override { return no_data_; }

protected:
  void read_box(const Box& box, std::span<float> out) const override {
    gdal::ErrorCapture errors;
    std::array<GUInt64, 3> start{};
    std::array<std::size_t, 3> count{};
    for (int a = 0; a < 3; ++a) {
      start[static_cast<std::size_t>(a)] = static_cast<GUInt64>(box.lo[a]);
      count[static_cast<std::size_t>(a)] = static_cast<std::size_t>(box.size(a));
    }
    // Null steps and strides: a contiguous C-order buffer of exactly the box, which is our layout.
    if (!array_->Read(start.data(), count.data(), nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float32),
                      out.data(), out.data(), out.size_bytes())) {
      std::string what = "cannot read the samples of array " + array_->GetFullName() + errors.text();
      ErrorContext where{path_, {}, {}, "box " + box.to_string(), {}};
      if (errors.first_error() == CPLE_FileIO || errors.first_error() == CPLE_OpenFailed)
        throw IoError(what, where, "check that the file is still there and readable");
      throw FormatError(what, where, "the file may be truncated or damaged");
    }
  }

private:
  std::string path_;
  std::string format_;
  // Declaration order matters: destroyed in reverse, the array before the dataset.
  gdal::DatasetPtr dataset_;
  std::shared_ptr<GDALGroup> root_;
  std::shared_ptr<GDALMDArray> array_;
  std::string array_name_; // the stored array's full name, "/chaos"
  Geometry geometry_;
  std::optional<float> no_data_; // the array's _FillValue, missing_value or fill_value
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
  Geometry geometry = gdal::read_geometry(*cube, *stored, path);
  std::string name = format_of(*dataset, format);
  bool declared = false;
  const double no_data = stored->GetNoDataValueAsDouble(&declared);
  std::string array_name = stored->GetFullName();
  stored.reset();
  return std::make_unique<GdalMdVolume>(path, std::move(name), std::move(dataset), std::move(root), std::move(cube),
                                        std::move(array_name), std::move(geometry),
                                        gdal::no_data_of(declared, no_data));
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
