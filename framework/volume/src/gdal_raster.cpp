// Reader of cubes stored as classic GDAL rasters (GeoTIFF, ENVI), in one of two layouts:
//
// - time slices, the convention of interpretation packages' exports and the default: band b
//   (1-based) is sample index k = b - 1, raster x (pixels) is inline index i, raster y (lines) is
//   crossline index j; the geotransform, when present, gives the survey affine.
// - inline slices, the layout geotandem's GeoTIFF writer uses: band b is inline index b - 1,
//   raster lines are crosslines (j) and pixels are samples (k), so the raster's C order
//   [band][line][pixel] is our [i][j][k]. Such files say so in the geotandem_layout metadata
//   item; files geotandem wrote before that item existed carry geotandem_* geometry items only,
//   and are read in this layout too.
//
// The GeoTIFF writer is in gdal_raster_write.cpp.

#include <numeric>
#include <optional>
#include <vector>

#include "formats.hpp"
#include "gdal_common.hpp"
#include "gdal_module.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/core/params.hpp"

namespace geotandem::volume::detail {
namespace {

enum class RasterLayout { time_slices, inline_slices };

// Reads boxes with one windowed RasterIO over the box's bands. Owns its dataset: GDAL datasets are
// not thread-safe, so use one GdalRasterVolume per thread.
class GdalRasterVolume final : public Volume {
public:
  GdalRasterVolume(std::string path, Format format, gdal::DatasetPtr dataset, RasterLayout layout, Geometry geometry,
                   std::optional<float> no_data, std::string assumed)
      : path_(std::move(path)), format_(format), dataset_(std::move(dataset)), layout_(layout),
        geometry_(std::move(geometry)), no_data_(no_data), assumed_(std::move(assumed)) {}

  ~GdalRasterVolume() override {
    gdal::ErrorCapture quiet;
    dataset_.reset();
  }

  const Geometry& geometry() const override { return geometry_; }
  std::string format() const override { return format_name(format_); }
  std::string source() const override { return path_; }
  std::vector<FormatDetail> format_details() const override {
    std::vector<FormatDetail> details;
    if (layout_ == RasterLayout::inline_slices)
      details.push_back(
          {"layout", "inline slices (band = inline, raster x = sample, y = crossline; written by geotandem)"});
    else
      details.push_back({"layout", "time slices (band = sample, raster x = inline, y = crossline)"});
    if (no_data_) details.push_back(gdal::no_data_detail(*no_data_));
    if (!assumed_.empty()) details.push_back({"assumed", assumed_});
    return details;
  }
  std::optional<float> declared_no_data() const override { return no_data_; }

protected:
  void read_box(const Box& box, std::span<float> out) const override {
    gdal::ErrorCapture errors;
    const auto ni = static_cast<int>(box.size(0));
    const auto nj = static_cast<int>(box.size(1));
    const auto nk = static_cast<int>(box.size(2));
    const GSpacing value = sizeof(float);
    CPLErr status = CE_None;
    std::vector<int> bands;
    if (layout_ == RasterLayout::inline_slices) {
      // Bands are inlines; the window is (pixels k0..k1, lines j0..j1).
      bands.resize(static_cast<std::size_t>(ni));
      std::iota(bands.begin(), bands.end(), static_cast<int>(box.lo[0]) + 1);
      status = dataset_->RasterIO(GF_Read, static_cast<int>(box.lo[2]), static_cast<int>(box.lo[1]), nk, nj, out.data(),
                                  nk, nj, GDT_Float32, ni, bands.data(), value, value * nk, value * nk * nj, nullptr);
    } else {
      // Bands are samples; the window is (pixels i0..i1, lines j0..j1). The buffer strides put
      // pixel x at i, line y at j and band b at k of the box's C order [i][j][k].
      bands.resize(static_cast<std::size_t>(nk));
      std::iota(bands.begin(), bands.end(), static_cast<int>(box.lo[2]) + 1);
      status = dataset_->RasterIO(GF_Read, static_cast<int>(box.lo[0]), static_cast<int>(box.lo[1]), ni, nj, out.data(),
                                  ni, nj, GDT_Float32, nk, bands.data(), value * nj * nk, value * nk, value, nullptr);
    }
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
  RasterLayout layout_;
  Geometry geometry_;
  std::optional<float> no_data_; // the first band's nodata (GeoTIFF's applies to every band)
  std::string assumed_;          // what the file does not say (assumed_of)
};

// The layout item when present; otherwise inline slices for files with geotandem_* geometry items
// (written by geotandem before the item existed), time slices for everything else.
RasterLayout layout_of(GDALDataset& dataset, const std::string& path) {
  if (const char* text = dataset.GetMetadataItem(gdal::raster_layout_key)) {
    const std::string value = text;
    if (value == gdal::inline_slices) return RasterLayout::inline_slices;
    if (value == gdal::time_slices) return RasterLayout::time_slices;
    throw FormatError(std::string("metadata item ") + gdal::raster_layout_key + " is '" + value + "'; expected '" +
                          gdal::inline_slices + "' or '" + gdal::time_slices + "'",
                      {path}, "repair or remove the item");
  }
  for (const gdal::GeometryField& field : gdal::geometry_fields())
    if (dataset.GetMetadataItem(field.key)) return RasterLayout::inline_slices;
  return RasterLayout::time_slices;
}

// The survey affine of a time-slice stack from the geotransform, which maps pixel corners:
// X = g0 + x g1 + y g2, Y = g3 + x g4 + y g5. Traces sit at pixel centres (x + 0.5, y + 0.5), and x
// is the inline index, y the crossline index.
SurveyAffine affine_of(const std::array<double, 6>& t) {
  SurveyAffine a;
  a.x0 = t[0] + 0.5 * t[1] + 0.5 * t[2];
  a.xi = t[1];
  a.xj = t[2];
  a.y0 = t[3] + 0.5 * t[4] + 0.5 * t[5];
  a.yi = t[4];
  a.yj = t[5];
  return a;
}

// Geometry: the shape from the layout; for time slices the affine from the geotransform when the
// file has one; then the geotandem_* metadata items of the default domain, which win. Missing
// items keep the defaults of Geometry, with the indices as line numbers.
Geometry geometry_of(GDALDataset& dataset, RasterLayout layout, const std::string& path) {
  Geometry g;
  const std::int64_t bands = dataset.GetRasterCount(), lines = dataset.GetRasterYSize(),
                     pixels = dataset.GetRasterXSize();
  g.shape = layout == RasterLayout::inline_slices ? Index3{bands, lines, pixels} : Index3{pixels, lines, bands};
  g.inline0 = 0.0;
  g.crossline0 = 0.0;
  bool from_transform = false;
  if (layout == RasterLayout::time_slices) {
    std::array<double, 6> transform{};
    if (dataset.GetGeoTransform(transform.data()) == CE_None) {
      g.affine = affine_of(transform);
      from_transform = true;
    }
  }
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
                      from_transform ? "the geotransform must map raster x and y to two independent map directions"
                                     : "repair the geotandem_* metadata items");
  }
  return g;
}

// What a classic raster leaves to the defaults, for a user to check: the sample axis (a time-slice
// stack has no place for it) and the survey's position (no geotransform); empty when the file says
// both.
std::string assumed_of(GDALDataset& dataset, const Geometry& g) {
  auto has = [&](std::initializer_list<const char*> keys) {
    for (const char* key : keys)
      if (dataset.GetMetadataItem(key)) return true;
    return false;
  };
  std::string out;
  if (!has({"geotandem_z0", "geotandem_dz", gdal::z_unit_key}))
    out = "the sample axis, " + number_text(g.z0) + " " + to_string(g.z_unit) + " at steps of " + number_text(g.dz) +
          " " + to_string(g.z_unit) +
          " (set the metadata items geotandem_z0, geotandem_dz and geotandem_z_unit, e.g. gdal_edit -mo "
          "geotandem_dz=2 -mo geotandem_z_unit=ms FILE)";
  std::array<double, 6> transform{};
  if (dataset.GetGeoTransform(transform.data()) != CE_None &&
      !has({"geotandem_x0", "geotandem_xi", "geotandem_xj", "geotandem_y0", "geotandem_yi", "geotandem_yj"})) {
    if (!out.empty()) out += "; ";
    out += "the survey's position, bins of 25 m from x 0, y 0 (the file has no geotransform; give it one with "
           "gdal_edit -a_ullr or gdal_translate)";
  }
  return out;
}

} // namespace

// What the file says: geotandem's metadata item, else the dataset's georeference (GeoTIFF keys,
// ENVI's coordinate system string).
std::optional<Crs> crs_of(GDALDataset& dataset, const std::string& path) {
  if (const char* text = dataset.GetMetadataItem(gdal::crs_key); text && *text)
    return gdal::crs_of_text(text, std::string("metadata item ") + gdal::crs_key, path);
  return gdal::crs_of_srs(dataset.GetSpatialRef(), "the raster's georeference", path);
}

std::unique_ptr<Volume> gdal::open_raster(const std::string& path, Format format, const OpenOptions& options) {
  const char* driver = format == Format::geotiff ? "GTiff" : format == Format::envi ? "ENVI" : nullptr;
  if (!driver) throw InvalidArgument(std::string("not a classic raster format: ") + format_name(format), {path});
  gdal::DatasetPtr dataset = gdal::open_dataset(path, GDAL_OF_RASTER, driver, format_name(format));
  gdal::ErrorCapture errors;
  if (dataset->GetRasterCount() < 1)
    throw FormatError("the raster has no band; a cube needs one band per time slice", {path});
  for (int b = 1; b <= dataset->GetRasterCount(); ++b) {
    GDALDataType type = dataset->GetRasterBand(b)->GetRasterDataType();
    if (type != GDT_Float32 && type != GDT_Float64)
      throw FormatError("band " + std::to_string(b) + " holds " + gdal::type_name(type) +
                            " samples; geotandem reads Float32 or Float64 cubes",
                        {path}, "convert the raster to Float32 (gdal_translate -ot Float32)");
  }
  const RasterLayout layout = layout_of(*dataset, path);
  Geometry geometry = geometry_of(*dataset, layout, path);
  try {
    if (auto crs = crs_of(*dataset, path)) geometry.crs = *crs;
  } catch (const FormatError&) {
    if (!options.crs) throw; // a user's CRS replaces it (open_volume)
  }
  int declared = FALSE;
  const double no_data = dataset->GetRasterBand(1)->GetNoDataValue(&declared);
  std::string assumed = assumed_of(*dataset, geometry);
  return std::make_unique<GdalRasterVolume>(path, format, std::move(dataset), layout, std::move(geometry),
                                            gdal::no_data_of(declared != FALSE, no_data), std::move(assumed));
}

} // namespace geotandem::volume::detail
