#pragma once
// Looking into a multidimensional file (netCDF-4, HDF5, Zarr) opened through GDAL: which array is
// the cube, in which axis order, and what geometry its attributes and coordinate variables give.

#include <gdal_priv.h>

#include <array>
#include <cstdint>
#include <memory>
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

} // namespace geotandem::volume::detail::gdal
