// The GDAL module's one exported entry point (gdal_module.hpp): the table of its readers and
// writers. Built into libgeotandem_volume_gdal.so only.
#include "gdal_module.hpp"

namespace {

const geotandem::volume::detail::GdalModule kModule{
    geotandem::volume::detail::kGdalModuleVersion,       &geotandem::volume::detail::gdal::open_md,
    &geotandem::volume::detail::gdal::open_md_dataset,   &geotandem::volume::detail::gdal::write_md,
    &geotandem::volume::detail::gdal::open_raster,       &geotandem::volume::detail::gdal::write_geotiff,
    &geotandem::volume::detail::gdal::parse_crs,         &geotandem::volume::detail::gdal::union_of_triangles,
    &geotandem::volume::detail::gdal::create_geopackage,
};

} // namespace

extern "C" __attribute__((visibility("default"))) const geotandem::volume::detail::GdalModule*
geotandem_volume_gdal_module() {
  return &kModule;
}
