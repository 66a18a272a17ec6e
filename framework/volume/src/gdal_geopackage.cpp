// GeoPackage writing and map polygon unions through GDAL/OGR and GEOS (module side of
// volume/geopackage.hpp).

#include <ogr_geometry.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "gdal_common.hpp"
#include "gdal_module.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::volume {

namespace detail {
namespace {

// A ring without its closing point, oriented as asked.
MapRing ring_of(const OGRLinearRing& ring, bool counter_clockwise) {
  MapRing out;
  const int n = ring.getNumPoints();
  for (int i = 0; i + 1 < n; ++i)
    out.push_back({ring.getX(i), ring.getY(i)});
  if (n > 0 && (ring.getX(0) != ring.getX(n - 1) || ring.getY(0) != ring.getY(n - 1)))
    out.push_back({ring.getX(n - 1), ring.getY(n - 1)});
  // isClockwise() tells the stored orientation; the shoelace sign says the same without a copy.
  double twice = 0.0;
  for (std::size_t i = 0; i < out.size(); ++i)
    twice += out[i][0] * out[(i + 1) % out.size()][1] - out[(i + 1) % out.size()][0] * out[i][1];
  if ((twice > 0.0) != counter_clockwise) std::reverse(out.begin(), out.end());
  return out;
}

void collect(const OGRGeometry& geometry, std::vector<MapPolygon>& out) {
  const auto type = wkbFlatten(geometry.getGeometryType());
  if (type == wkbPolygon) {
    const auto& polygon = *geometry.toPolygon();
    if (!polygon.getExteriorRing() || polygon.getExteriorRing()->getNumPoints() < 4) return;
    MapPolygon p;
    p.outer = ring_of(*polygon.getExteriorRing(), true);
    for (int h = 0; h < polygon.getNumInteriorRings(); ++h)
      p.holes.push_back(ring_of(*polygon.getInteriorRing(h), false));
    out.push_back(std::move(p));
  } else if (type == wkbMultiPolygon || type == wkbGeometryCollection) {
    const auto& collection = *geometry.toGeometryCollection();
    for (int g = 0; g < collection.getNumGeometries(); ++g)
      collect(*collection.getGeometryRef(g), out);
  }
}

OGRPolygon polygon_of(const MapPolygon& polygon) {
  OGRPolygon out;
  auto add = [&](const MapRing& ring) {
    auto* r = new OGRLinearRing();
    for (const MapPoint& p : ring)
      r->addPoint(p[0], p[1]);
    if (!ring.empty()) r->addPoint(ring.front()[0], ring.front()[1]);
    out.addRingDirectly(r);
  };
  add(polygon.outer);
  for (const MapRing& hole : polygon.holes)
    add(hole);
  return out;
}

class OgrGeoPackageWriter final : public GeoPackageWriter {
public:
  OgrGeoPackageWriter(const std::string& path, const GeoPackageLayout& layout)
      : path_(path), fields_(layout.fields), undefined_crs_(layout.crs.empty()) {
    gdal::register_drivers();
    gdal::ErrorCapture errors;
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
    if (!driver) fail("GDAL was built without the GPKG driver", errors);
    dataset_.reset(driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    if (!dataset_) fail("cannot create the GeoPackage", errors);
    std::unique_ptr<OGRSpatialReference> srs;
    if (!layout.crs.empty()) {
      srs = std::make_unique<OGRSpatialReference>();
      if (srs->importFromWkt(layout.crs.wkt.c_str()) != OGRERR_NONE)
        fail("the CRS's WKT does not read back: " + layout.crs.label(), errors);
      // x east, y north, whatever axis order the CRS's definition states.
      srs->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    }
    CPLStringList options;
    if (!layout.description.empty()) options.SetNameValue("DESCRIPTION", layout.description.c_str());
    polygons_ = dataset_->CreateLayer(layout.polygons.c_str(), srs.get(), wkbMultiPolygon, options.List());
    if (!polygons_) fail("cannot create layer " + layout.polygons, errors);
    points_ = dataset_->CreateLayer(layout.points.c_str(), srs.get(), wkbPoint, options.List());
    if (!points_) fail("cannot create layer " + layout.points, errors);
    for (OGRLayer* layer : {polygons_, points_})
      for (const GisField& field : fields_) {
        OGRFieldDefn definition(field.name.c_str(), OFTReal);
        switch (field.type) {
        case GisFieldType::integer: definition.SetType(OFTInteger64); break;
        case GisFieldType::real: definition.SetType(OFTReal); break;
        case GisFieldType::text: definition.SetType(OFTString); break;
        case GisFieldType::boolean:
          definition.SetType(OFTInteger);
          definition.SetSubType(OFSTBoolean);
          break;
        }
        if (layer->CreateField(&definition) != OGRERR_NONE) fail("cannot create field " + field.name, errors);
      }
    // One transaction for everything: a GeoPackage written feature by feature commits each one.
    if (dataset_->StartTransaction() != OGRERR_NONE) fail("cannot start a transaction", errors);
  }

  ~OgrGeoPackageWriter() override {
    gdal::ErrorCapture quiet;
    dataset_.reset();
  }

  void add_polygons(const std::vector<MapPolygon>& polygons, const std::vector<GisValue>& values) override {
    gdal::ErrorCapture errors;
    OGRFeature feature(polygons_->GetLayerDefn());
    set_values(feature, values);
    if (!polygons.empty()) {
      auto* multi = new OGRMultiPolygon();
      for (const MapPolygon& p : polygons) {
        const OGRPolygon polygon = polygon_of(p);
        multi->addGeometry(&polygon); // copies
      }
      feature.SetGeometryDirectly(multi);
    }
    if (polygons_->CreateFeature(&feature) != OGRERR_NONE) fail("cannot write a footprint", errors);
  }

  void add_point(const MapPoint& point, const std::vector<GisValue>& values) override {
    gdal::ErrorCapture errors;
    OGRFeature feature(points_->GetLayerDefn());
    set_values(feature, values);
    feature.SetGeometryDirectly(new OGRPoint(point[0], point[1]));
    if (points_->CreateFeature(&feature) != OGRERR_NONE) fail("cannot write a centroid", errors);
  }

  void finish() override {
    gdal::ErrorCapture errors;
    if (undefined_crs_) {
      // A layer created without an SRS gets srs_id 0, GeoPackage's "Undefined geographic SRS":
      // degrees of latitude and longitude, which QGIS would then assume. Without a CRS the
      // coordinates are projected x and y of no known system: srs_id -1, the standard's "Undefined
      // Cartesian SRS" (GDAL reads it back as a LOCAL_CS of that name, no authority). The layers'
      // description says "no CRS given". Done here: GDAL creates a layer's tables with its first
      // feature.
      for (OGRLayer* layer : {polygons_, points_}) {
        const std::string name = layer->GetName();
        for (const char* table : {"gpkg_geometry_columns", "gpkg_contents"}) {
          const std::string sql =
              std::string("UPDATE ") + table + " SET srs_id = -1 WHERE lower(table_name) = lower('" + name + "')";
          dataset_->ReleaseResultSet(dataset_->ExecuteSQL(sql.c_str(), nullptr, nullptr));
        }
      }
    }
    if (dataset_->CommitTransaction() != OGRERR_NONE) fail("cannot commit the features", errors);
    gdal::close_written(std::move(dataset_), path_);
  }

private:
  [[noreturn]] void fail(const std::string& what, const gdal::ErrorCapture& errors) const {
    throw IoError(what + errors.text(), {path_}, "check free disk space and write permission");
  }

  void set_values(OGRFeature& feature, const std::vector<GisValue>& values) const {
    if (values.size() != fields_.size())
      throw InvalidArgument("a feature with " + std::to_string(values.size()) + " values for " +
                                std::to_string(fields_.size()) + " fields",
                            {path_});
    for (std::size_t n = 0; n < values.size(); ++n) {
      const int field = static_cast<int>(n);
      const GisValue& value = values[n];
      if (std::holds_alternative<std::monostate>(value))
        feature.SetFieldNull(field);
      else if (const auto* i = std::get_if<std::int64_t>(&value))
        feature.SetField(field, static_cast<GIntBig>(*i));
      else if (const auto* d = std::get_if<double>(&value))
        feature.SetField(field, *d);
      else if (const auto* t = std::get_if<std::string>(&value))
        feature.SetField(field, t->c_str());
      else if (const auto* b = std::get_if<bool>(&value))
        feature.SetField(field, *b ? 1 : 0);
    }
  }

  std::string path_;
  std::vector<GisField> fields_;
  gdal::DatasetPtr dataset_;
  OGRLayer* polygons_ = nullptr; // owned by the dataset
  OGRLayer* points_ = nullptr;
  bool undefined_crs_ = false; // no CRS given: srs_id -1 (finish)
};

} // namespace

std::vector<MapPolygon> gdal::union_of_triangles(std::span<const MapTriangle> triangles) {
  if (!OGRGeometryFactory::haveGEOS())
    throw InvalidArgument("GDAL was built without GEOS, which the union of polygons needs", {},
                          "install GDAL with GEOS (Debian's libgdal has it)");
  ErrorCapture errors;
  OGRMultiPolygon pieces;
  double largest = 0.0;
  for (const MapTriangle& t : triangles)
    for (const MapPoint& p : t)
      largest = std::max({largest, std::abs(p[0]), std::abs(p[1])});
  for (const MapTriangle& t : triangles) {
    // Triangles seen edge-on (a wall of the body) have no area on the map. What is "no area" is
    // the rounding of this cross product: its differences of coordinates of magnitude `largest`
    // carry errors of about eps * largest each, times the triangle's own edges. (A threshold
    // scaled by largest^2 alone, 45 m^2 at 6.7e6 m, dropped real triangles of a finely meshed
    // body: footprints with holes, smaller than the body, some missing their centroid.)
    const double ux = t[1][0] - t[0][0], uy = t[1][1] - t[0][1];
    const double vx = t[2][0] - t[0][0], vy = t[2][1] - t[0][1];
    const double twice = ux * vy - vx * uy;
    const double edges = std::abs(ux) + std::abs(uy) + std::abs(vx) + std::abs(vy);
    const double tiny = 8.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, largest) * edges;
    if (!(std::abs(twice) > tiny)) continue;
    auto* polygon = new OGRPolygon();
    auto* ring = new OGRLinearRing();
    for (int c : {0, 1, 2, 0})
      ring->addPoint(t[static_cast<std::size_t>(c)][0], t[static_cast<std::size_t>(c)][1]);
    polygon->addRingDirectly(ring);
    pieces.addGeometryDirectly(polygon);
  }
  std::vector<MapPolygon> out;
  if (pieces.IsEmpty()) return out;
  std::unique_ptr<OGRGeometry> merged(pieces.UnionCascaded());
  // GEOS can refuse a union over slivers it finds inconsistent: the zero-width buffer of the pieces
  // is the same area, computed another way.
  if (!merged) merged.reset(pieces.Buffer(0.0));
  if (!merged)
    throw DataError("GEOS cannot merge the " + std::to_string(pieces.getNumGeometries()) + " triangles of a footprint" +
                    errors.text());
  collect(*merged, out);
  return out;
}

std::unique_ptr<GeoPackageWriter> gdal::create_geopackage(const std::string& path, const GeoPackageLayout& layout) {
  return std::make_unique<OgrGeoPackageWriter>(path, layout);
}

} // namespace detail
} // namespace geotandem::volume
