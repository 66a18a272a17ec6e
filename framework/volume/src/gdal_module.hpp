#pragma once
// The GDAL-backed formats (netCDF-4, HDF5, Zarr, GeoTIFF, ENVI) live in a module of their own,
// libgeotandem_volume_gdal.so, which the volume library loads the first time one of them is opened
// or written (gdal_loader.cpp). GDAL and the hundred libraries it needs are then mapped only by the
// processes that read or write such a file: linked in, they cost every geotandem process about
// 30 MiB of resident memory and most of its start-up time (docs/formats-gdal.md, "The GDAL module").
//
// The module exports one C function, kGdalModuleEntry, which returns the table below. Both sides
// are built from the same tree, so the table holds C++ function pointers; its version guards
// against a module left over from another build.

#include <cstdint>
#include <memory>
#include <string>

#include "formats.hpp"
#include "geotandem/volume/geopackage.hpp"

namespace geotandem::volume::detail {

struct GdalModule {
  std::uint32_t version;
  std::unique_ptr<Volume> (*open_md)(const std::string& path, Format format, const OpenOptions& options);
  std::unique_ptr<Volume> (*open_md_dataset)(GDALDataset* dataset, const std::string& name, const OpenOptions& options);
  void (*write_md)(const Volume& volume, const std::string& path, Format format, const WriteOptions& options,
                   Progress& progress, const CancelToken& cancel);
  std::unique_ptr<Volume> (*open_raster)(const std::string& path, Format format, const OpenOptions& options);
  void (*write_geotiff)(const Volume& volume, const std::string& path, const WriteOptions& options, Progress& progress,
                        const CancelToken& cancel);
  Crs (*parse_crs)(const std::string& text);
  std::vector<MapPolygon> (*union_of_triangles)(std::span<const MapTriangle> triangles);
  std::unique_ptr<GeoPackageWriter> (*create_geopackage)(const std::string& path, const GeoPackageLayout& layout);
};

// Bumped whenever GdalModule or a signature in it changes.
inline constexpr std::uint32_t kGdalModuleVersion = 2;
inline constexpr const char* kGdalModuleEntry = "geotandem_volume_gdal_module";
inline constexpr const char* kGdalModuleFile = "libgeotandem_volume_gdal.so";
// Where to load the module from instead of beside libgeotandem_volume (packagers, tests).
inline constexpr const char* kGdalModuleVariable = "GEOTANDEM_GDAL_MODULE";

// The module's side: the functions the table points to. Their own names, in their own namespace,
// so that none of them can be interposed by the forwarding functions of formats.hpp.
namespace gdal {
std::unique_ptr<Volume> open_md(const std::string& path, Format format, const OpenOptions& options);
std::unique_ptr<Volume> open_md_dataset(GDALDataset* dataset, const std::string& name, const OpenOptions& options);
void write_md(const Volume& volume, const std::string& path, Format format, const WriteOptions& options,
              Progress& progress, const CancelToken& cancel);
std::unique_ptr<Volume> open_raster(const std::string& path, Format format, const OpenOptions& options);
void write_geotiff(const Volume& volume, const std::string& path, const WriteOptions& options, Progress& progress,
                   const CancelToken& cancel);
Crs parse_crs(const std::string& text);
std::vector<MapPolygon> union_of_triangles(std::span<const MapTriangle> triangles);
std::unique_ptr<GeoPackageWriter> create_geopackage(const std::string& path, const GeoPackageLayout& layout);
} // namespace gdal

// The library's side: the module's table, loaded on first use (thread-safe). When it cannot be
// loaded, throws IoError naming `file` (the cube being read or written), its format, the module's
// path and the loader's reason.
const GdalModule& gdal_module(const std::string& file, Format format);
// The same for work that is not a cube's format: `what` says what needs the module ("checking the
// CRS", "the GeoPackage export"), `file` what it was about (a path, or the CRS's text).
const GdalModule& gdal_module(const std::string& file, const std::string& what);

} // namespace geotandem::volume::detail
