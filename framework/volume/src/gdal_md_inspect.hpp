#pragma once
// Looking into a multidimensional file (netCDF-4, HDF5, Zarr) opened through GDAL: which array is
// the cube, in which axis order, and what geometry its attributes and coordinate variables give.

#include <gdal_priv.h>

#include <memory>
#include <string>

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

// The geometry of `array` (already in cube order). Start from the defaults of Geometry with the
// indices as line numbers, take line numbers and the sample axis from 1-D coordinate variables when
// the dimensions have them, then the geotandem_* attributes of `attributes_of` (the array as
// stored) override. Throws FormatError naming `path` when an attribute holds nonsense.
Geometry read_geometry(const GDALMDArray& array, const GDALMDArray& attributes_of, const std::string& path);

} // namespace geotandem::volume::detail::gdal
