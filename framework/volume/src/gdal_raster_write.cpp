// GeoTIFF writer: one Float32 band per inline slice (band b = inline index b - 1), raster width =
// samples, height = crosslines; tiled, band-interleaved, geometry as geotandem_* metadata items
// of the default domain and the layout as geotandem_layout = inline_slices, so that the reader
// does not take the bands for time slices (docs/formats-gdal.md).

#include <filesystem>
#include <limits>
#include <numeric>
#include <vector>

#include "formats.hpp"
#include "gdal_common.hpp"
#include "gdal_module.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::volume::detail {
namespace {

[[noreturn]] void fail(const std::string& what, const gdal::ErrorCapture& errors, const std::string& path,
                       const std::string& block = {}) {
  throw IoError(what + errors.text(), {path, {}, {}, block, {}}, "check free disk space and write permission");
}

// TIFF tiles must be multiples of 16 pixels on both sides.
int tile_edge(int chunk) {
  return std::max(16, (chunk + 15) / 16 * 16);
}

} // namespace

void gdal::write_geotiff(const Volume& volume, const std::string& path, const WriteOptions& options, Progress& progress,
                         const CancelToken& cancel) {
  const Geometry& g = volume.geometry();
  constexpr auto int_max = static_cast<std::int64_t>(std::numeric_limits<int>::max());
  if (g.shape[0] > 65535 || g.shape[1] > int_max || g.shape[2] > int_max)
    throw InvalidArgument("a GeoTIFF holds at most 65535 inlines (bands); this cube has " + std::to_string(g.shape[0]),
                          {path}, "write netCDF-4 (.nc) or Zarr (.zarr) instead");
  gdal::register_drivers();
  gdal::ErrorCapture errors;
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (!driver) fail("GDAL was built without the GTiff driver", errors, path);
  const int tile = tile_edge(options.chunk);
  CPLStringList create_options;
  create_options.SetNameValue("TILED", "YES");
  create_options.SetNameValue("BLOCKXSIZE", std::to_string(tile).c_str());
  create_options.SetNameValue("BLOCKYSIZE", std::to_string(tile).c_str());
  create_options.SetNameValue("INTERLEAVE", "BAND");
  // Classic TIFF stops at 4 GiB; switch to BigTIFF when the cube might need it.
  create_options.SetNameValue("BIGTIFF", "IF_SAFER");
  gdal::DatasetPtr dataset(driver->Create(path.c_str(), static_cast<int>(g.shape[2]), static_cast<int>(g.shape[1]),
                                          static_cast<int>(g.shape[0]), GDT_Float32, create_options.List()));
  if (!dataset) fail("cannot create the GeoTIFF", errors, path);
  try {
    for (const gdal::GeometryField& field : gdal::geometry_fields())
      dataset->SetMetadataItem(field.key, gdal::format_double(gdal::field_value(g, field)).c_str());
    dataset->SetMetadataItem(gdal::z_unit_key, to_string(g.z_unit));
    // As a metadata item, not as GeoTIFF keys: raster x and y are samples and crosslines here.
    if (!g.crs.empty()) dataset->SetMetadataItem(gdal::crs_key, g.crs.wkt.c_str());
    // Says that the bands are inlines, not time slices (the reader's default for other files).
    dataset->SetMetadataItem(gdal::raster_layout_key, gdal::inline_slices);
    // Boxes as deep as the chunk in inlines and one tile wide, so that each tile is written once.
    const Index3 block{options.chunk, tile, tile};
    std::vector<int> bands;
    gdal::stream_boxes(volume, block, "writing GeoTIFF", progress, cancel,
                       [&](const Box& box, std::span<const float> samples) {
                         bands.resize(static_cast<std::size_t>(box.size(0)));
                         std::iota(bands.begin(), bands.end(), static_cast<int>(box.lo[0]) + 1);
                         const auto nk = static_cast<int>(box.size(2));
                         const auto nj = static_cast<int>(box.size(1));
                         const GSpacing pixel = sizeof(float);
                         // RasterIO takes a non-const buffer for both directions; GF_Write only reads it.
                         auto* data = const_cast<float*>(samples.data());
                         if (dataset->RasterIO(GF_Write, static_cast<int>(box.lo[2]), static_cast<int>(box.lo[1]), nk,
                                               nj, data, nk, nj, GDT_Float32, static_cast<int>(bands.size()),
                                               bands.data(), pixel, pixel * nk, pixel * nk * nj, nullptr) != CE_None)
                           fail("cannot write the samples", errors, path, "box " + box.to_string());
                       });
    gdal::close_written(std::move(dataset), path);
  } catch (...) {
    dataset.reset();
    std::error_code ec;
    std::filesystem::remove(path, ec);
    throw;
  }
}

} // namespace geotandem::volume::detail
