// Loading the GDAL module on first use (gdal_module.hpp), and the volume library's forwarding
// functions for the GDAL-backed formats (formats.hpp).
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "gdal_module.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/volume/crs.hpp"
#include "geotandem/volume/geopackage.hpp"

namespace geotandem::volume::detail {
namespace {

// The module's path: $GEOTANDEM_GDAL_MODULE, or the file beside this library (the build tree's lib
// directory, or the installed one).
std::string module_path() {
  if (const char* path = std::getenv(kGdalModuleVariable); path && *path) return path;
  Dl_info info{};
  if (::dladdr(reinterpret_cast<const void*>(&module_path), &info) != 0 && info.dli_fname)
    return (std::filesystem::path(info.dli_fname).parent_path() / kGdalModuleFile).string();
  return kGdalModuleFile; // the loader's own search path
}

struct Loaded {
  const GdalModule* module = nullptr;
  std::string path;
  std::string why; // when module is null
};

Loaded load() {
  Loaded out;
  out.path = module_path();
  // The module takes this library's symbols (and geotandem_core's) from the process. A process that
  // loaded this library privately does not offer them: Python loads an extension module, and with
  // it this library, with RTLD_LOCAL. Made global here (RTLD_NOLOAD: it is loaded already), this
  // library and its dependencies are offered to the module. Never closed, as the module.
  Dl_info self{};
  if (::dladdr(reinterpret_cast<const void*>(&module_path), &self) != 0 && self.dli_fname)
    (void)::dlopen(self.dli_fname, RTLD_NOW | RTLD_NOLOAD | RTLD_GLOBAL);
  ::dlerror();
  // Never closed: volumes made by the module outlive any caller that could close it.
  void* handle = ::dlopen(out.path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = ::dlerror();
    out.why = why ? why : "the loader gave no reason";
    return out;
  }
  void* entry = ::dlsym(handle, kGdalModuleEntry);
  if (!entry) {
    out.why = out.path + " has no entry point '" + kGdalModuleEntry + "'";
    return out;
  }
  const auto* module = reinterpret_cast<const GdalModule* (*)()>(entry)();
  if (!module || module->version != kGdalModuleVersion) {
    out.why = out.path + " comes from another geotandem build (table version " +
              (module ? std::to_string(module->version) : std::string("none")) + ", this library expects " +
              std::to_string(kGdalModuleVersion) + ")";
    return out;
  }
  out.module = module;
  return out;
}

} // namespace

const GdalModule& gdal_module(const std::string& file, const std::string& what) {
  static const Loaded loaded = load(); // once per process, thread-safe
  if (!loaded.module)
    throw IoError(what + " needs geotandem's GDAL module, which cannot be loaded: " + loaded.why, {file},
                  "install geotandem again (the module, " + std::string(kGdalModuleFile) +
                      ", belongs beside libgeotandem_volume) or point " + kGdalModuleVariable +
                      " at it; SEG-Y and raw cubes do not need it");
  return *loaded.module;
}

const GdalModule& gdal_module(const std::string& file, Format format) {
  return gdal_module(file, std::string(format_name(format)));
}

std::unique_ptr<Volume> open_gdal_md(const std::string& path, Format format, const OpenOptions& options) {
  return gdal_module(path, format).open_md(path, format, options);
}
std::unique_ptr<Volume> open_gdal_dataset(GDALDataset* dataset, const std::string& name, const OpenOptions& options) {
  const GdalModule* module = nullptr;
  try {
    module = &gdal_module(name, Format::netcdf);
  } catch (const IoError&) {
    // The dataset is ours to close, also on error. Its caller made it, so GDAL is loaded.
    using Close = int (*)(void*);
    if (auto close = reinterpret_cast<Close>(::dlsym(RTLD_DEFAULT, "GDALClose")); close && dataset) close(dataset);
    throw;
  }
  return module->open_md_dataset(dataset, name, options);
}
void write_gdal_md(const Volume& volume, const std::string& path, Format format, const WriteOptions& options,
                   Progress& progress, const CancelToken& cancel) {
  gdal_module(path, format).write_md(volume, path, format, options, progress, cancel);
}
std::unique_ptr<Volume> open_gdal_raster(const std::string& path, Format format, const OpenOptions& options) {
  return gdal_module(path, format).open_raster(path, format, options);
}
void write_geotiff(const Volume& volume, const std::string& path, const WriteOptions& options, Progress& progress,
                   const CancelToken& cancel) {
  gdal_module(path, Format::geotiff).write_geotiff(volume, path, options, progress, cancel);
}

} // namespace geotandem::volume::detail

namespace geotandem::volume {

Crs parse_crs(const std::string& text) {
  return detail::gdal_module(text, "checking the CRS").parse_crs(text);
}

std::vector<MapPolygon> union_of_triangles(std::span<const MapTriangle> triangles) {
  return detail::gdal_module("", "the union of map triangles").union_of_triangles(triangles);
}

std::unique_ptr<GeoPackageWriter> create_geopackage(const std::string& path, const GeoPackageLayout& layout) {
  return detail::gdal_module(path, "writing a GeoPackage").create_geopackage(path, layout);
}

} // namespace geotandem::volume
