// The store's CRS in every export, and the GeoPackage of footprints and centroids (issue 54 parts
// 1 and 2), read back with GDAL/OGR (and with fiona, from Debian's python3-fiona, where installed).

#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <utility>

#include "base64_decode.hpp"
#include "export_fixture.hpp"
#include "geotandem/mesh/measure.hpp"
#include "geotandem/volume/crs.hpp"

namespace geotandem::store::testing {
namespace {

// The convex hull's area of points (monotone chain): for a convex body such as the fixtures'
// ellipsoids the footprint is exactly the hull of its vertices on the map, an oracle independent
// of the union the export computes.
double hull_area(std::vector<std::array<double, 2>> p) {
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return 0.0;
  auto cross = [](const auto& o, const auto& a, const auto& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  std::vector<std::array<double, 2>> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0)
      --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], p[i - 1]) <= 0)
      --k;
    hull[k++] = p[i - 1];
  }
  hull.resize(k - 1);
  double twice = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i)
    twice += hull[i][0] * hull[(i + 1) % hull.size()][1] - hull[(i + 1) % hull.size()][0] * hull[i][1];
  return std::abs(twice) / 2.0;
}

struct Dataset {
  GDALDataset* handle = nullptr;
  explicit Dataset(const std::filesystem::path& path) {
    GDALAllRegister();
    handle =
        GDALDataset::FromHandle(GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
  }
  ~Dataset() {
    if (handle) GDALClose(GDALDataset::ToHandle(handle));
  }
};

// A VTK string array of one tuple in binary: base64 of a UInt64 byte count, then the string's
// characters ended by 0 (as vtkXMLWriter writes a vtkStringArray).
std::string vtp_string(const std::string& vtp, const std::string& name) {
  const std::string tag = "<Array type=\"String\" Name=\"" + name + "\" NumberOfTuples=\"1\" format=\"binary\">";
  const auto at = vtp.find(tag);
  if (at == std::string::npos) return "(missing)";
  const auto begin = vtp.find_first_not_of(" \n", at + tag.size());
  const auto end = vtp.find_first_of(" \n<", begin);
  const auto bytes = decode_base64(std::string_view(vtp).substr(begin, end - begin));
  if (!bytes || bytes->size() < 9) return "(not base64)";
  std::uint64_t count = 0;
  std::memcpy(&count, bytes->data(), 8);
  const std::string payload = bytes->substr(8);
  if (count != payload.size() || payload.back() != '\0') return "(bad byte count or no 0)";
  return payload.substr(0, payload.size() - 1);
}

// A ring-shaped body (a torus about the vertical through (ci, cj, ck), in index coordinates): its
// footprint is an annulus whose hole holds the body's centroid. Quads split into triangles, all
// oriented alike; `nv` even so that the innermost and outermost vertex rings exist.
mesh::Component torus_component(std::uint64_t key, const volume::Geometry& g, double big, double small, int nu,
                                int nv) {
  const double ci = 30, cj = 25, ck = 20;
  mesh::Component c;
  c.key = key;
  const double two_pi = 2.0 * std::numbers::pi;
  for (int a = 0; a < nu; ++a)
    for (int b = 0; b < nv; ++b) {
      const double u = two_pi * a / nu, v = two_pi * b / nv;
      const double radius = big + small * std::cos(v);
      c.surface.points.push_back({ci + radius * std::cos(u), cj + radius * std::sin(u), ck + small * std::sin(v)});
    }
  auto at = [&](int a, int b) { return static_cast<std::uint32_t>((a % nu) * nv + (b % nv)); };
  for (int a = 0; a < nu; ++a)
    for (int b = 0; b < nv; ++b) {
      c.surface.triangles.push_back({at(a, b), at(a + 1, b), at(a + 1, b + 1)});
      c.surface.triangles.push_back({at(a, b), at(a + 1, b + 1), at(a, b + 1)});
    }
  const auto world = mesh::to_world(c.surface, g);
  auto& st = c.stats;
  st.vertex_count = world.points.size();
  st.triangle_count = world.triangles.size();
  st.box_min = st.box_max = world.points.front();
  for (const auto& p : world.points)
    for (int d = 0; d < 3; ++d) {
      st.box_min[d] = std::min(st.box_min[d], p[d]);
      st.box_max[d] = std::max(st.box_max[d], p[d]);
    }
  // The solid's centroid: the torus's centre, by symmetry.
  st.centroid = g.world(ci, cj, ck);
  st.closed = true;
  st.volume = 2.0 * std::numbers::pi * std::numbers::pi * big * small * small;
  return c;
}

class GisExportTest : public ::testing::Test {
protected:
  void make_store(bool with_crs) {
    volume::Geometry g = test_geometry();
    if (with_crs) g.crs = volume::parse_crs("EPSG:23031");
    store_.emplace(ComponentStore::create(scratch_.path() / "store", g));
    LocalSink sink(*store_, {"local", std::nullopt, 8});
    for (std::uint64_t key : {5, 12, 31, 44, 57, 63})
      sink.commit(make_component(key, g, 2));
    sink.close();
    rows_ = store_->query();
  }

  ExportSummary run(const std::filesystem::path& out, ExportOptions options, const std::vector<ComponentRow>& rows) {
    NullProgress progress;
    return export_components(*store_, rows, out, options, progress, CancelToken{});
  }

  // b.ts, b.vtp, b.ply and b.gpkg of every row, in the scratch directory.
  void export_all() {
    ExportOptions options;
    for (const auto& [format, name] :
         {std::pair{ExportFormat::tsurf, "b.ts"}, std::pair{ExportFormat::vtp, "b.vtp"},
          std::pair{ExportFormat::ply, "b.ply"}, std::pair{ExportFormat::gpkg, "b.gpkg"}}) {
      options.format = format;
      run(scratch_.path() / name, options, rows_);
    }
  }

  geotandem::testing::ScratchDir scratch_;
  std::optional<ComponentStore> store_;
  std::vector<ComponentRow> rows_;
};

TEST_F(GisExportTest, TsurfVtpPlyAndGeoPackageSayTheSameCrs) {
  make_store(true);
  export_all();

  const std::string label = "ED50 / UTM zone 31N (EPSG:23031)";
  const std::string ts = slurp(scratch_.path() / "b.ts");
  EXPECT_NE(ts.find("GOCAD_ORIGINAL_COORDINATE_SYSTEM\nNAME \"" + label +
                    "\"\nAXIS_NAME \"X\" \"Y\" \"TWT\"\n"
                    "AXIS_UNIT \"m\" \"m\" \"ms\"\nZPOSITIVE Time\nEND_ORIGINAL_COORDINATE_SYSTEM"),
            std::string::npos)
      << ts.substr(0, 400);
  const std::string vtp = slurp(scratch_.path() / "b.vtp");
  EXPECT_EQ(vtp_string(vtp, "crs"), label);
  EXPECT_EQ(vtp_string(vtp, "crs_units"), "m m ms");
  OGRSpatialReference epsg, from_vtp;
  ASSERT_EQ(epsg.importFromEPSG(23031), OGRERR_NONE);
  ASSERT_EQ(from_vtp.importFromWkt(vtp_string(vtp, "crs_wkt").c_str()), OGRERR_NONE);
  EXPECT_TRUE(from_vtp.IsSame(&epsg));
  const std::string ply = slurp(scratch_.path() / "b.ply");
  EXPECT_NE(ply.find("comment crs " + label + "\ncomment units x m y m z ms\n"), std::string::npos);

  Dataset gpkg(scratch_.path() / "b.gpkg");
  ASSERT_NE(gpkg.handle, nullptr);
  for (const char* name : {"footprints", "centroids"}) {
    OGRLayer* layer = gpkg.handle->GetLayerByName(name);
    ASSERT_NE(layer, nullptr) << name;
    ASSERT_NE(layer->GetSpatialRef(), nullptr) << name;
    EXPECT_TRUE(layer->GetSpatialRef()->IsSame(&epsg)) << name;
    EXPECT_STREQ(layer->GetSpatialRef()->GetAuthorityCode(nullptr), "23031");
  }
}

TEST_F(GisExportTest, WithoutACrsEveryExportSaysNoCrsGiven) {
  make_store(false);
  export_all();
  EXPECT_NE(slurp(scratch_.path() / "b.ts").find("GOCAD_ORIGINAL_COORDINATE_SYSTEM\n# no CRS given\nNAME Default\n"),
            std::string::npos);
  EXPECT_EQ(vtp_string(slurp(scratch_.path() / "b.vtp"), "crs"), "no CRS given");
  EXPECT_NE(slurp(scratch_.path() / "b.ply").find("comment crs no CRS given\n"), std::string::npos);
  Dataset gpkg(scratch_.path() / "b.gpkg");
  ASSERT_NE(gpkg.handle, nullptr);
  // No CRS is invented: not GDAL's default for a layer without one (srs_id 0, "Undefined
  // geographic SRS", which says degrees of latitude and longitude), but srs_id -1, the standard's
  // "Undefined Cartesian SRS", which GDAL reads back as a LOCAL_CS of that name with no authority.
  for (const char* table : {"gpkg_contents", "gpkg_geometry_columns"}) {
    const std::string sql = std::string("SELECT table_name AS name, srs_id AS srs FROM ") + table +
                            " WHERE table_name IN ('footprints', 'centroids') ORDER BY table_name";
    OGRLayer* srs_ids = gpkg.handle->ExecuteSQL(sql.c_str(), nullptr, nullptr);
    ASSERT_NE(srs_ids, nullptr) << table;
    std::vector<std::string> seen;
    for (auto& row : *srs_ids) {
      seen.push_back(row->GetFieldAsString("name"));
      EXPECT_EQ(row->GetFieldAsInteger("srs"), -1) << table << " " << seen.back();
    }
    gpkg.handle->ReleaseResultSet(srs_ids);
    EXPECT_EQ(seen, (std::vector<std::string>{"centroids", "footprints"})) << table;
  }
  for (const char* name : {"footprints", "centroids"}) {
    OGRLayer* layer = gpkg.handle->GetLayerByName(name);
    ASSERT_NE(layer, nullptr);
    if (const OGRSpatialReference* srs = layer->GetSpatialRef()) {
      EXPECT_TRUE(srs->IsLocal()) << name;
      EXPECT_FALSE(srs->IsGeographic()) << name;
      EXPECT_FALSE(srs->IsProjected()) << name;
      EXPECT_EQ(srs->GetAuthorityName(nullptr), nullptr) << name;
    }
    EXPECT_NE(std::string(layer->GetMetadataItem("DESCRIPTION")).find("no CRS given"), std::string::npos) << name;
  }
}

TEST_F(GisExportTest, FootprintsContainTheCentroidsAndAgreeWithTheStore) {
  make_store(true);
  ASSERT_TRUE(store_->geometry().crs.code == "EPSG:23031");
  store_->save_selection("kept", {12, 57, 63}, "{}");
  ExportOptions options;
  options.format = ExportFormat::gpkg;
  run(scratch_.path() / "all.gpkg", options, rows_);
  Dataset gpkg(scratch_.path() / "all.gpkg");
  ASSERT_NE(gpkg.handle, nullptr);
  OGRLayer* polygons = gpkg.handle->GetLayerByName("footprints");
  OGRLayer* points = gpkg.handle->GetLayerByName("centroids");
  ASSERT_TRUE(polygons && points);
  EXPECT_EQ(polygons->GetFeatureCount(), static_cast<GIntBig>(rows_.size()));
  EXPECT_EQ(points->GetFeatureCount(), static_cast<GIntBig>(rows_.size()));

  std::map<std::uint64_t, const ComponentRow*> by_key;
  for (const auto& row : rows_)
    by_key[row.key] = &row;
  std::set<std::uint64_t> seen;
  polygons->ResetReading();
  for (auto& feature : *polygons) {
    const auto key = static_cast<std::uint64_t>(feature->GetFieldAsInteger64("key"));
    ASSERT_TRUE(by_key.count(key)) << key;
    seen.insert(key);
    const ComponentRow& row = *by_key[key];
    SCOPED_TRACE("key " + std::to_string(key));
    EXPECT_DOUBLE_EQ(feature->GetFieldAsDouble("volume"), row.stats.volume);
    EXPECT_DOUBLE_EQ(feature->GetFieldAsDouble("area"), row.stats.area);
    EXPECT_DOUBLE_EQ(feature->GetFieldAsDouble("azimuth"), row.stats.azimuth);
    EXPECT_DOUBLE_EQ(feature->GetFieldAsDouble("dip"), row.stats.dip);
    EXPECT_DOUBLE_EQ(feature->GetFieldAsDouble("centroid_z"), row.stats.centroid[2]);
    EXPECT_EQ(feature->GetFieldAsInteger64("triangle_count"), static_cast<GIntBig>(row.location.triangle_count));
    EXPECT_EQ(feature->GetFieldAsInteger("closed") != 0, row.stats.closed);
    const bool kept = key == 12 || key == 57 || key == 63;
    EXPECT_EQ(feature->GetFieldAsInteger("in_kept") != 0, kept);
    const OGRGeometry* footprint = feature->GetGeometryRef();
    ASSERT_NE(footprint, nullptr);
    const double area = footprint->toMultiPolygon()->get_Area();
    // The shoelace sum over map coordinates of ~6.7e6 m: each term's rounding is about
    // eps * |x| * |y| (~1e-3 m^2 here), so an area of n vertices is good to about n * 4 * eps * |x| * |y|
    // whatever the order of the sums (OGR's get_Area, the export's area_of relative to a vertex and
    // the hull below each sum differently). Exactness beyond that (1e-9 relative on ~1e4 m^2) is
    // not in the doubles.
    OGREnvelope box;
    footprint->getEnvelope(&box);
    const double reach =
        std::max(std::abs(box.MinX), std::abs(box.MaxX)) * std::max(std::abs(box.MinY), std::abs(box.MaxY));
    const double rounding =
        4.0 * std::numeric_limits<double>::epsilon() * reach * static_cast<double>(store_->read(row).points.size() + 8);
    EXPECT_NEAR(feature->GetFieldAsDouble("footprint_area"), area, rounding);
    // The oracle: the hull of the body's vertices on the map.
    std::vector<std::array<double, 2>> map;
    for (const auto& p : store_->read(row).points)
      map.push_back({p[0], p[1]});
    EXPECT_NEAR(area, hull_area(map), 2.0 * rounding);
    const OGRPoint centroid(row.stats.centroid[0], row.stats.centroid[1]);
    EXPECT_TRUE(footprint->Contains(&centroid));
  }
  EXPECT_EQ(seen.size(), rows_.size());
  points->ResetReading();
  for (auto& feature : *points) {
    const ComponentRow& row = *by_key.at(static_cast<std::uint64_t>(feature->GetFieldAsInteger64("key")));
    const OGRPoint* point = feature->GetGeometryRef()->toPoint();
    EXPECT_DOUBLE_EQ(point->getX(), row.stats.centroid[0]);
    EXPECT_DOUBLE_EQ(point->getY(), row.stats.centroid[1]);
  }
}

// The footprint is the outline seen from above, not a hull: a ring-shaped body's has its hole, and
// the centroid of the solid lies in it (outside the footprint), as for any C- or ring-shaped body.
// The oracle: the annulus between the outermost and innermost vertex rings, regular polygons of nu
// sides, in index units times the bin's area.
TEST_F(GisExportTest, ARingShapedBodysFootprintKeepsItsHoleWithTheCentroidInIt) {
  volume::Geometry g = test_geometry();
  g.crs = volume::parse_crs("EPSG:23031");
  store_.emplace(ComponentStore::create(scratch_.path() / "store", g));
  const double big = 12, small = 4;
  const int nu = 48, nv = 16;
  {
    LocalSink sink(*store_, {"local", std::nullopt, 8});
    sink.commit(torus_component(77, g, big, small, nu, nv));
    sink.close();
  }
  rows_ = store_->query();
  ExportOptions options;
  options.format = ExportFormat::gpkg;
  run(scratch_.path() / "ring.gpkg", options, rows_);
  Dataset gpkg(scratch_.path() / "ring.gpkg");
  ASSERT_NE(gpkg.handle, nullptr);
  OGRLayer* polygons = gpkg.handle->GetLayerByName("footprints");
  ASSERT_NE(polygons, nullptr);
  ASSERT_EQ(polygons->GetFeatureCount(), 1);
  polygons->ResetReading();
  std::unique_ptr<OGRFeature> feature(polygons->GetNextFeature());
  ASSERT_NE(feature, nullptr);
  const OGRMultiPolygon* footprint = feature->GetGeometryRef()->toMultiPolygon();
  ASSERT_EQ(footprint->getNumGeometries(), 1);
  EXPECT_EQ(footprint->getGeometryRef(0)->getNumInteriorRings(), 1);
  const auto& f = g.affine;
  const double bin_area = std::abs(f.xi * f.yj - f.xj * f.yi);
  const double polygon = nu / 2.0 * std::sin(2.0 * std::numbers::pi / nu);
  const double expected = polygon * ((big + small) * (big + small) - (big - small) * (big - small)) * bin_area;
  EXPECT_NEAR(footprint->get_Area(), expected, 1e-6 * expected);
  EXPECT_NEAR(feature->GetFieldAsDouble("footprint_area"), expected, 1e-6 * expected);
  const auto& centroid = rows_.front().stats.centroid;
  const OGRPoint point(centroid[0], centroid[1]);
  EXPECT_FALSE(footprint->Contains(&point)) << "the centroid of a ring lies in its hole";
  // A point on the ring itself (the middle of the tube, on the map) is inside.
  const auto on_ring = g.world(30 + big, 25, 20);
  const OGRPoint ring_point(on_ring[0], on_ring[1]);
  EXPECT_TRUE(footprint->Contains(&ring_point));
}

TEST_F(GisExportTest, ASelectionExportHoldsExactlyThatSelection) {
  make_store(true);
  store_->save_selection("kept", {12, 57, 63}, "{}");
  Query q;
  q.selection = "kept";
  ExportOptions options;
  options.format = ExportFormat::gpkg;
  options.selection = "kept";
  run(scratch_.path() / "kept.gpkg", options, store_->query(q));
  Dataset gpkg(scratch_.path() / "kept.gpkg");
  ASSERT_NE(gpkg.handle, nullptr);
  for (const char* name : {"footprints", "centroids"}) {
    OGRLayer* layer = gpkg.handle->GetLayerByName(name);
    ASSERT_NE(layer, nullptr);
    std::set<std::uint64_t> keys;
    for (auto& feature : *layer)
      keys.insert(static_cast<std::uint64_t>(feature->GetFieldAsInteger64("key")));
    EXPECT_EQ(keys, (std::set<std::uint64_t>{12, 57, 63})) << name;
    EXPECT_NE(std::string(layer->GetMetadataItem("DESCRIPTION")).find("selection kept"), std::string::npos);
  }
}

TEST_F(GisExportTest, TheGeoPackageIsWrittenWholeAndRefusesPerComponent) {
  make_store(true);
  ExportOptions options;
  options.format = ExportFormat::gpkg;
  const auto target = scratch_.path() / "b.gpkg";
  run(target, options, rows_);
  // Nothing but the file itself is left beside it.
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(scratch_.path()))
    files += entry.path().filename().string().find("b.gpkg") != std::string::npos;
  EXPECT_EQ(files, 1u);
  EXPECT_THROW(run(target, options, rows_), IoError); // exists, no overwrite
  options.overwrite = true;
  EXPECT_NO_THROW(run(target, options, rows_));
  options.per_component = true;
  EXPECT_THROW(run(scratch_.path() / "dir", options, rows_), InvalidArgument);
}

#ifdef GEOTANDEM_SYSTEM_PYTHON3
// What geopandas users get: fiona (Debian's python3-fiona) reads the layers, their CRS and counts.
TEST_F(GisExportTest, FionaReadsTheLayersAndTheirCrs) {
  make_store(true);
  ExportOptions options;
  options.format = ExportFormat::gpkg;
  run(scratch_.path() / "b.gpkg", options, rows_);
  const auto script = scratch_.path() / "read.py";
  std::ofstream(script)
      << "import sys\n"
         "try:\n    import fiona\nexcept ImportError:\n    print('no fiona'); sys.exit(0)\n"
         "from osgeo import osr\n"
         "for name in fiona.listlayers(sys.argv[1]):\n"
         "    with fiona.open(sys.argv[1], layer=name) as layer:\n"
         "        s = osr.SpatialReference(); s.ImportFromWkt(layer.crs_wkt)\n"
         "        e = osr.SpatialReference(); e.ImportFromEPSG(23031)\n"
         "        print(name, len(layer), bool(s.IsSame(e)), sorted(int(f['properties']['key']) for f in layer))\n";
  const std::string command = std::string(GEOTANDEM_SYSTEM_PYTHON3) + " " + script.string() + " " +
                              (scratch_.path() / "b.gpkg").string() + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe))
    out += buffer;
  ASSERT_EQ(::pclose(pipe), 0) << out;
  ASSERT_EQ(out.find("no fiona"), std::string::npos) << "python3-fiona is not installed (scripts/setup.sh installs it)";
  EXPECT_NE(out.find("footprints 6 True [5, 12, 31, 44, 57, 63]"), std::string::npos) << out;
  EXPECT_NE(out.find("centroids 6 True [5, 12, 31, 44, 57, 63]"), std::string::npos) << out;
}
#endif

} // namespace
} // namespace geotandem::store::testing
