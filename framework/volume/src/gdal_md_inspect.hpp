#pragma once
// Looking into a multidimensional file (netCDF-4, HDF5, Zarr) opened through GDAL: which array is
// the cube, in which axis order, and what geometry its attributes and coordinate variables give.

#include <gdal_priv.h>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geotandem/volume/geometry.hpp"

namespace geotandem::volume::detail::gdal {

// The cube's array. `requested` is OpenOptions::variable: a name or a full name ("/group/name");
// empty means the only 3-D floating-point array of the file (searched in every group).
// Throws FormatError naming `path`: no such array (listing the candidates), several candidates,
// none at all, or an array that is not 3-D or not Float32/Float64.
std::shared_ptr<GDALMDArray> choose_array(GDALGroup& root, const std::string& requested, const std::string& path);

// The array viewed in (inline, crossline, sample) order. Dimension names decide when all three are
// recognised (iline/inline/il/x, xline/crossline/xl/y, twt/time/depth/z/sample); otherwise the
// stored order is taken as (inline, crossline, sample), the order geotandem writes, unless a name
// contradicts it (a sample axis stored first or second): a FormatError naming `path`.
std::shared_ptr<GDALMDArray> in_cube_order(const std::shared_ptr<GDALMDArray>& array, const std::string& path);

// Where the stored lines of a survey with missing lines sit in the cube: for the inline (0) and
// crossline (1) axes, grid[a][m] is the cube index of stored line m (increasing), or grid[a] is
// empty when the axis misses no line (cube index = stored index).
struct LineGaps {
  std::array<std::vector<std::int64_t>, 2> grid;
  std::array<std::string, 2> missing; // "506, 507 (2 of 9 lines)" for messages, or empty
  bool any() const { return !grid[0].empty() || !grid[1].empty(); }
};

// The geometry of `array` (already in cube order). Start from the defaults of Geometry with the
// indices as line numbers, take line numbers and the sample axis from 1-D coordinate variables when
// the dimensions have them, then the geotandem_* attributes of `attributes_of` (the array as
// stored) override. Throws FormatError naming `path` when an attribute holds nonsense.
// Line numbers that skip lines (steps that are whole multiples of the smallest one) describe a
// survey with missing lines: with `read_missing` (the NaN fill policy) the cube spans the whole
// grid and `gaps` says where the stored lines go; otherwise a FormatError names the missing lines.
Geometry read_geometry(const GDALMDArray& array, const GDALMDArray& attributes_of, const std::string& path,
                       bool read_missing = false, LineGaps* gaps = nullptr);

// The CRS the file declares for the cube `stored` (the array as stored), in this order: geotandem's
// own attribute (geotandem_crs, a WKT), the spatial reference the driver finds (netCDF CF
// grid_mapping, Zarr _CRS), the variable a `grid_mapping` attribute names (its crs_wkt or
// spatial_ref attribute, as xarray/rioxarray write them), a `crs` text attribute of the array, then
// of the root group (an EPSG code or a WKT). nullopt when none. Throws FormatError naming `path`
// (and what held it) when OSR does not know what the file says.
std::optional<Crs> read_crs(GDALGroup& root, const GDALMDArray& stored, const std::string& path);

} // namespace geotandem::volume::detail::gdal
