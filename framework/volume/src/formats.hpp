#pragma once
// Per-format readers and writers behind open_volume/write_volume. Internal to the volume part.
// Each reader returns a Volume that reads lazily by box; each writer streams from a Volume.

#include <memory>
#include <string>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/volume/io.hpp"

namespace geotandem::volume::detail {

enum class Format { netcdf, hdf5, zarr, geotiff, envi, segy, raw, unknown };

// Looks at the file (signature bytes, sidecars, directory layout); never at the extension alone.
Format sniff_format(const std::string& path);
const char* format_name(Format format);

// GDAL multidimensional API: netCDF-4, HDF5 (read only), Zarr. These and the two GDAL raster
// functions below forward to the GDAL module, loaded on first use (gdal_module.hpp, gdal_loader.cpp);
// the readers and writers themselves are gdal_md.cpp, gdal_md_write.cpp and gdal_raster*.cpp.
std::unique_ptr<Volume> open_gdal_md(const std::string& path, Format format, const OpenOptions& options);
// open_gdal_dataset without the NaN guard and the geometry check.
std::unique_ptr<Volume> open_gdal_dataset(GDALDataset* dataset, const std::string& name, const OpenOptions& options);
void write_gdal_md(const Volume& volume, const std::string& path, Format format, const WriteOptions& options,
                   Progress& progress, const CancelToken& cancel);

// GDAL classic rasters, GeoTIFF and ENVI: time-slice stacks (band = sample), or inline slices in
// files geotandem wrote.
std::unique_ptr<Volume> open_gdal_raster(const std::string& path, Format format, const OpenOptions& options);
void write_geotiff(const Volume& volume, const std::string& path, const WriteOptions& options, Progress& progress,
                   const CancelToken& cancel);

// SEG-Y through segyio. (segy.cpp)
std::unique_ptr<Volume> open_segy(const std::string& path, const OpenOptions& options);
void write_segy(const Volume& volume, const std::string& path, const WriteOptions& options, Progress& progress,
                const CancelToken& cancel);

// write_segy_like (io.hpp). (segy_like_writer.cpp)
void write_segy_like(const Volume& volume, const std::string& like, const OpenOptions& options, const std::string& path,
                     const WriteOptions& write, Progress& progress, const CancelToken& cancel);

// Raw little-endian float32, C order [inline][crossline][sample], with FILE.json sidecar. (raw.cpp)
std::unique_ptr<Volume> open_raw(const std::string& path, const OpenOptions& options);
void write_raw(const Volume& volume, const std::string& path, const WriteOptions& options, Progress& progress,
               const CancelToken& cancel);
// The same, reading `volume` in slabs `thickness` samples thick along `axis` (0, 1 or 2) and whole
// along the other two: a file stored in chunks that thin along that axis is then decoded once.
// Along axis 2 the file is written in runs of `thickness` samples, one per trace.
// Reports as `task`. A failed or cancelled write removes what it wrote.
void write_raw_slabs(const Volume& volume, const std::string& path, int axis, std::int64_t thickness,
                     const std::string& task, Progress& progress, const CancelToken& cancel);

// Wraps a reader so that NaN and infinite samples follow the policy. (nan_guard.cpp)
std::unique_ptr<Volume> guard_nan(std::unique_ptr<Volume> inner, const OpenOptions& options);

} // namespace geotandem::volume::detail
