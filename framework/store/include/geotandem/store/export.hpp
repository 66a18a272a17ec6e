#pragma once
// Exports of stored components to the formats interpreters open: PLY (ParaView, MeshLab,
// CloudCompare), OBJ, VTP (ParaView; per-body key, volume and azimuth as cell and field data) and
// GOCAD TSurf (Petrel, SKUA-GOCAD, OpendTect), and the inventory as a GIS layer: a GeoPackage
// (QGIS, ArcGIS, geopandas) of body footprints and centroids with every measure of the index.
// Coordinates are world coordinates; every format names the store's CRS, or says "no CRS given".

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/store/store.hpp"

namespace geotandem::store {

enum class ExportFormat { ply, obj, vtp, tsurf, gpkg };

// The export formats as a table, like the steps' registry: the export step's `format` choices,
// `geotandem store export --format`, the docs and the writers are read from it, and it is the only
// list of their names. Adding a format: a writer (export_<format>.cpp) and one row in export.cpp.
struct ExportFormatInfo {
  ExportFormat format;
  const char* name;    // as recipes and the command line spell it; also the file extension
  const char* summary; // which programs open it
};
// ply, obj, vtp, ts, gpkg: in that order.
const std::vector<ExportFormatInfo>& export_formats();
// Their names, in the same order.
std::vector<std::string> export_format_names();

// A name of export_formats() (or "tsurf" for ts); throws InvalidArgument otherwise, with the
// nearest name.
ExportFormat parse_export_format(const std::string& text);
// The file extension without dot: ply, obj, vtp, ts, gpkg.
const char* file_extension(ExportFormat format);

struct ExportOptions {
  ExportFormat format = ExportFormat::ply;
  // One file per component, named <prefix><key>.<ext>, into the directory `out` (created when
  // missing). Otherwise one file `out` holding every component.
  bool per_component = false;
  std::string name_prefix = "geobody_";
  // PLY only: vertex coordinates as float32 instead of float64 (half the size; about 1e-7
  // relative precision, a few centimetres at typical map coordinates).
  bool ply_float32 = false;
  // Replace files that already exist (otherwise an existing file is an error, before anything is
  // written).
  bool overwrite = false;
  // Verify every record first and leave the damaged ones out (listed in ExportSummary::skipped)
  // instead of stopping at the first one.
  bool skip_damaged = false;
  // Keep the caps that close bodies cut by the cube's border (docs/caps.md). Off: a cut body is
  // exported as the open surface the isovalue makes, without the triangles on the cube's faces.
  bool caps = true;
  // GeoPackage only: the selection the rows were filtered by ("" when none), named in the layers'
  // description. Without one, every named selection of the store becomes a boolean column
  // in_<name>.
  std::string selection;
};

struct ExportSummary {
  std::vector<std::filesystem::path> files;
  std::uint64_t components = 0;
  std::uint64_t vertices = 0;
  std::uint64_t triangles = 0;
  std::vector<std::uint64_t> skipped; // keys of damaged components left out (skip_damaged)
};

// GeoPackage (ExportFormat::gpkg): one file with two layers, `footprints` (each body's outline
// seen from above: the union of its surface's triangles projected on the map, holes included) and
// `centroids` (points), both with the key and every measure of the index as attributes
// (footprint_area on both), in the store's CRS. One file only: per_component is refused.
//
// Writes `rows` (from ComponentStore::query) to `out`. Each file is written beside its final name
// and renamed into place when complete. Streams component by component: memory holds one
// component at a time. Throws InvalidArgument for an empty `rows` or an output inside a store
// directory (only the store writes there), IoError when a file exists (without `overwrite`) or
// cannot be written, FormatError for a damaged record (without `skip_damaged`), Cancelled.
ExportSummary export_components(const ComponentStore& store, const std::vector<ComponentRow>& rows,
                                const std::filesystem::path& out, const ExportOptions& options, Progress& progress,
                                const CancelToken& cancel);

} // namespace geotandem::store
