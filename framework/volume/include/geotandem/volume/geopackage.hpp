#pragma once
// Writing GeoPackages (OGC GPKG: SQLite with geometry tables) through GDAL/OGR, for the store's
// GIS export: a polygon layer and a point layer sharing one attribute table layout and one CRS.
// Nothing here knows of components: the store hands over polygons, points and values.
// Loads the GDAL module on first use (gdal_module.hpp).

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "geotandem/volume/geometry.hpp"

namespace geotandem::volume {

enum class GisFieldType { integer, real, text, boolean };
struct GisField {
  std::string name;
  GisFieldType type = GisFieldType::real;
};
// A feature's value of one field; monostate is NULL.
using GisValue = std::variant<std::monostate, std::int64_t, double, std::string, bool>;

using MapPoint = std::array<double, 2>;
using MapRing = std::vector<MapPoint>; // closed implicitly: the last point is not the first repeated
struct MapPolygon {
  MapRing outer;              // counter-clockwise
  std::vector<MapRing> holes; // clockwise
};
using MapTriangle = std::array<MapPoint, 3>;

// The union of `triangles` (any orientation; degenerate ones are skipped) as polygons with holes,
// through GEOS. Throws InvalidArgument when GDAL was built without GEOS.
std::vector<MapPolygon> union_of_triangles(std::span<const MapTriangle> triangles);
// Area of polygons (outer rings less holes), by the shoelace formula.
double area_of(const std::vector<MapPolygon>& polygons);

struct GeoPackageLayout {
  std::vector<GisField> fields;        // the same columns on both layers
  Crs crs;                             // empty: GeoPackage's "undefined Cartesian" SRS (srs_id -1)
  std::string polygons = "footprints"; // layer names
  std::string points = "centroids";
  std::string description; // each layer's gpkg_contents.description
};

class GeoPackageWriter {
public:
  virtual ~GeoPackageWriter() = default;
  // `values` in the order of GeoPackageLayout::fields. A feature with no polygon gets a NULL
  // geometry. Throw IoError naming the file when OGR refuses.
  virtual void add_polygons(const std::vector<MapPolygon>& polygons, const std::vector<GisValue>& values) = 0;
  virtual void add_point(const MapPoint& point, const std::vector<GisValue>& values) = 0;
  // Commits and closes the file (everything is written in one transaction per layer). Throws
  // IoError when GDAL fails while flushing. Dropping the writer without finish() leaves a file
  // that the caller removes.
  virtual void finish() = 0;
};

// Creates a new GeoPackage at `path` (which must not exist: OGR refuses existing files; its
// extension should be .gpkg). Throws IoError naming the file.
std::unique_ptr<GeoPackageWriter> create_geopackage(const std::string& path, const GeoPackageLayout& layout);

} // namespace geotandem::volume
