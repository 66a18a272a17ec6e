// Reader of cubes stored as classic GDAL rasters (GeoTIFF, ENVI), one band per inline slice:
// band b (1-based) is inline index b - 1, raster lines are crosslines (j) and pixels are samples
// (k), so a raster's C order [band][line][pixel] is our [i][j][k]. The GeoTIFF writer is in
// gdal_raster_write.cpp.

#include <numeric>
#include <vector>

#include "formats.hpp"
#include "gdal_common.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::volume::detail {
namespace {

// Reads boxes with one windowed RasterIO over the box's bands. Owns its dataset: GDAL datasets are
// not thread-safe, so use one GdalRasterVolume per thread.
class GdalRasterVolume final : public Volume {
public:
  GdalRasterVolume(std::string path, Format format, gdal::DatasetPtr dataset, Geometry geometry)
      : path_(std::move(path)), format_(format), dataset_(std::move(dataset)), geometry_(std::move(geometry)) {}

  ~GdalRasterVolume() override {
    gdal::ErrorCapture quiet;
    dataset_.reset();
  }

  const Geometry& geometry() const override { return geometry_; }
  std::string format() const override { return format_name(format_); }
  std::string source() const override { return path_; }

protected:
  void read_box(const Box& box, std::span<float> out) const override {
    gdal::ErrorCapture errors;
    std::vector<int> bands(static_cast<std::size_t>(box.size(0)));
    std::iota(bands.begin(), bands.end(), static_cast<int>(box.lo[0]) + 1);
    const auto nk = static_cast<int>(box.size(2));
    const auto nj = static_cast<int>(box.size(1));
    const GSpacing pixel = sizeof(float);
    const GSpacing line = pixel * nk;
    const GSpacing band = line * nj;
    CPLErr status =
        dataset_->RasterIO(GF_Read, static_cast<int>(box.lo[2]), static_cast<int>(box.lo[1]), nk, nj, out.data(), nk,
                           nj, GDT_Float32, static_cast<int>(bands.size()), bands.data(), pixel, line, band, nullptr);
    if (status != CE_None) {
      std::string what = "cannot read the samples" + errors.text();
      ErrorContext where{path_, {}, {}, "box " + box.to_string(), {}};
      if (errors.first_error() == CPLE_FileIO || errors.first_error() == CPLE_OpenFailed)
        throw IoError(what, where, "check that the file is still there and readable");
      throw FormatError(what, where, "the file may be truncated or damaged");
    }
  }

private:
  std::string path_;
  Format format_;
  gdal::DatasetPtr dataset_;
  Geometry geometry_;
};

// Geometry from the geotandem_* metadata items of the default domain; missing items keep the
// defaults of Geometry, with the indices as line numbers.
Geometry geometry_of(GDALDataset& dataset, const std::string& path) {
  Geometry g;
  g.shape = {dataset.GetRasterCount(), dataset.GetRasterYSize(), dataset.GetRasterXSize()};
  g.inline0 = 0.0;
  g.crossline0 = 0.0;
  for (const gdal::GeometryField& field : gdal::geometry_fields()) {
    const char* text = dataset.GetMetadataItem(field.key);
    if (!text) continue;
    auto value = gdal::parse_double(text);
    if (!value)
      throw FormatError(std::string("metadata item ") + field.key + " is '" + text + "', not a number", {path},
                        "repair or remove the item");
    field.field(g) = *value;
  }
  if (const char* text = dataset.GetMetadataItem(gdal::z_unit_key)) {
    try {
      g.z_unit = parse_sample_unit(text);
    } catch (const InvalidArgument&) {
      throw FormatError(std::string("metadata item ") + gdal::z_unit_key + " is '" + text + "'; expected 'ms' or 'm'",
                        {path}, "repair the item");
    }
  }
  try {
    g.validate();
  } catch (const InvalidArgument& error) {
    throw FormatError("the stored geometry is unusable: " + error.message(), {path},
                      "repair the geotandem_* metadata items");
  }
  return g;
}

} // namespace

std::unique_ptr<Volume> open_gdal_raster(const std::string& path, Format format, const OpenOptions&) {
  const char* driver = format == Format::geotiff ? "GTiff" : format == Format::envi ? "ENVI" : nullptr;
  if (!driver) throw InvalidArgument(std::string("not a classic raster format: ") + format_name(format), {path});
  gdal::DatasetPtr dataset = gdal::open_dataset(path, GDAL_OF_RASTER, driver, format_name(format));
  gdal::ErrorCapture errors;
  if (dataset->GetRasterCount() < 1)
    throw FormatError("the raster has no band; a cube needs one band per inline", {path});
  for (int b = 1; b <= dataset->GetRasterCount(); ++b) {
    GDALDataType type = dataset->GetRasterBand(b)->GetRasterDataType();
    if (type != GDT_Float32 && type != GDT_Float64)
      throw FormatError("band " + std::to_string(b) + " holds " + gdal::type_name(type) +
                            " samples; geotandem reads Float32 or Float64 cubes",
                        {path}, "convert the raster to Float32 (gdal_translate -ot Float32)");
  }
  Geometry geometry = geometry_of(*dataset, path);
  return std::make_unique<GdalRasterVolume>(path, format, std::move(dataset), std::move(geometry));
}

} // namespace geotandem::volume::detail
