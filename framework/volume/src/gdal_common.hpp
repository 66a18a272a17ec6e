#pragma once
// Shared by the GDAL-backed readers and writers (gdal_md*.cpp, gdal_raster*.cpp): one-time driver
// registration, capture of GDAL's messages into our exceptions, owning dataset handles, the names
// under which a cube's geometry is stored (docs/formats-gdal.md), and the chunk-by-chunk streaming
// loop of the writers.
//
// Thread safety: GDAL datasets are not thread-safe. Every Volume made here owns its own dataset
// handle; use one Volume per thread (open the file once per thread).

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::volume::detail::gdal {

// Registers GDAL's drivers once per process. GDAL keeps its driver manager as a process-wide
// global: there is no way to pass one down, so the first caller registers and later calls are free.
void register_drivers();

// While alive, collects GDAL's warnings and errors of the calling thread (GDAL keeps one handler
// stack per thread) instead of letting them reach stderr, so they end up in our error text.
class ErrorCapture {
public:
  ErrorCapture();
  ~ErrorCapture();
  ErrorCapture(const ErrorCapture&) = delete;
  ErrorCapture& operator=(const ErrorCapture&) = delete;

  // A CE_Failure or CE_Fatal was reported since construction or the last clear().
  bool failed() const { return failed_; }
  // The error number of the first failure (CPLE_None when none).
  CPLErrorNum first_error() const { return first_error_; }
  // "; GDAL: msg1; msg2" (at most a few messages), or "" when GDAL said nothing.
  std::string text() const;
  void clear();

private:
  static void CPL_STDCALL handle(CPLErr level, CPLErrorNum number, const char* message);

  std::vector<std::string> messages_;
  bool failed_ = false;
  CPLErrorNum first_error_ = CPLE_None;
};

struct DatasetCloser {
  void operator()(GDALDataset* dataset) const;
};
// Owns a dataset; closing flushes it (release every group, array and dimension handle first).
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

// Opens `path` with GDALOpenEx restricted to `driver` (a GDAL short name). `flags` adds
// GDAL_OF_RASTER or GDAL_OF_MULTIDIM_RASTER. Throws FormatError naming the file with GDAL's reason.
DatasetPtr open_dataset(const std::string& path, unsigned flags, const char* driver, const std::string& format);

// Closes a dataset that was written; throws IoError naming `path` when GDAL reports a failure
// while flushing.
void close_written(DatasetPtr dataset, const std::string& path);

// A no-data value the file declares (GeoTIFF's nodata, ENVI's data ignore value, netCDF's
// _FillValue or missing_value, Zarr's fill_value), as the float samples hold it: nullopt when none
// is declared, or when it is NaN (NaN samples are missing anyway). The readers report it
// (Volume::declared_no_data) and the NaN policy treats such samples as missing (volume/io.hpp):
// read as values, -999.25 or -3.4e38 would pass into the attributes and the isovalue tests as
// seismic amplitudes.
std::optional<float> no_data_of(bool declared, double value);
// How `geotandem info` shows the declared value (key kNoDataDetail).
FormatDetail no_data_detail(float no_data);

// Geometry storage. Numbers are stored under these keys (as Float64 attributes in netCDF/Zarr, as
// "%.17g" text metadata items in GeoTIFF); the sample unit as the text "ms" or "m" under
// z_unit_key. A missing key leaves the field as the reader's default.
struct GeometryField {
  const char* key;
  double& (*field)(Geometry&);
};
std::span<const GeometryField> geometry_fields();
inline constexpr const char* z_unit_key = "geotandem_z_unit";
// Classic rasters (GeoTIFF, ENVI): which axis the bands hold, as a metadata item of the default
// domain. geotandem's writer marks its files inline_slices; files without the item are time-slice
// stacks unless they carry geotandem_* geometry items (docs/formats-gdal.md).
inline constexpr const char* raster_layout_key = "geotandem_layout";
inline constexpr const char* inline_slices = "inline_slices";
inline constexpr const char* time_slices = "time_slices";
double field_value(const Geometry& geometry, const GeometryField& field);
// The CRS geotandem writes: a WKT text attribute of the array (netCDF, Zarr) or a metadata item
// (GeoTIFF). Read before what the driver finds (a CF grid_mapping, GeoTIFF keys).
inline constexpr const char* crs_key = "geotandem_crs";

// The CRS of `srs` (name, code, WKT, linear unit); InvalidArgument for a geographic CRS, naming
// `what`. (gdal_crs.cpp)
Crs describe(const OGRSpatialReference& srs, const std::string& what);
// A CRS a file declares, as text (an attribute) or as the driver's spatial reference; `where` says
// which ("attribute crs of array /amp"). Null or empty: nullopt. Throws FormatError naming `path`
// when OSR does not know it or it is geographic, with the hint to give one with --crs.
std::optional<Crs> crs_of_text(const std::string& text, const std::string& where, const std::string& path);
std::optional<Crs> crs_of_srs(const OGRSpatialReference* srs, const std::string& where, const std::string& path);

// Text that parses back to the same double; and its inverse (nullopt unless the whole text is a
// finite number).
std::string format_double(double value);
std::optional<double> parse_double(const char* text);

// GDAL's name of a data type ("Float32", "Int16", ...).
std::string type_name(GDALDataType type);

// Streams `source` in boxes of `block` samples aligned on multiples of `block` from the origin
// (clipped at the far faces), in C order of the boxes: reads each box, hands it to `write`,
// reports progress in boxes and checks `cancel` between boxes.
void stream_boxes(const Volume& source, const Index3& block, const std::string& label, Progress& progress,
                  const CancelToken& cancel, const std::function<void(const Box&, std::span<const float>)>& write);

} // namespace geotandem::volume::detail::gdal
