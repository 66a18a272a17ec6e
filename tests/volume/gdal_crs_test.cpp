// Coordinate reference systems (issue 54 part 1): parsed through OSR, refused when wrong, read from
// files other tools wrote (a CF netCDF written with GDAL, a GeoTIFF, a Zarr `crs` attribute),
// written back by every GDAL writer and the raw sidecar, replaced by a user's.

#include <ogr_spatialref.h>

#include <filesystem>

#include "gdal_fixtures.hpp"
#include "geotandem/volume/crs.hpp"
#include "scratch.hpp"

namespace {

namespace gv = geotandem::volume;
using namespace gdal_fixtures;
using geotandem::testing::ScratchDir;

// OSR's own view of a CRS: an independent check of what parse_crs keeps.
bool same_as_epsg(const std::string& wkt, int code) {
  OGRSpatialReference a, b;
  if (a.importFromWkt(wkt.c_str()) != OGRERR_NONE || b.importFromEPSG(code) != OGRERR_NONE) return false;
  return a.IsSame(&b);
}

std::string invalid_message(const std::string& text) {
  try {
    gv::parse_crs(text);
  } catch (const geotandem::InvalidArgument& e) {
    return e.what();
  }
  ADD_FAILURE() << "'" << text << "' was accepted";
  return {};
}

TEST(Crs, EpsgCodesAreNamedWithTheirUnits) {
  const gv::Crs utm = gv::parse_crs("EPSG:23031");
  EXPECT_EQ(utm.name, "ED50 / UTM zone 31N");
  EXPECT_EQ(utm.code, "EPSG:23031");
  EXPECT_EQ(utm.unit, "m");
  EXPECT_DOUBLE_EQ(utm.metres_per_unit, 1.0);
  EXPECT_TRUE(same_as_epsg(utm.wkt, 23031));
  EXPECT_EQ(utm.label(), "ED50 / UTM zone 31N (EPSG:23031)");

  const gv::Crs feet = gv::parse_crs("epsg:2227"); // NAD83 / California zone 3 (ftUS)
  EXPECT_EQ(feet.unit, "ftUS");
  EXPECT_NEAR(feet.metres_per_unit, 1200.0 / 3937.0, 1e-12);
  EXPECT_TRUE(same_as_epsg(feet.wkt, 2227));
  const gv::Crs international = gv::parse_crs("EPSG:2222"); // NAD83 / Arizona East (ft)
  EXPECT_EQ(international.unit, "ft");
  EXPECT_DOUBLE_EQ(international.metres_per_unit, 0.3048);
}

TEST(Crs, AWktWithoutIdentifierIsRecognised) {
  OGRSpatialReference srs;
  ASSERT_EQ(srs.importFromEPSG(32631), OGRERR_NONE);
  char* wkt = nullptr;
  ASSERT_EQ(srs.exportToWkt(&wkt), OGRERR_NONE); // WKT 1 with AUTHORITY nodes
  const gv::Crs crs = gv::parse_crs(wkt);
  CPLFree(wkt);
  EXPECT_EQ(crs.name, "WGS 84 / UTM zone 31N");
  EXPECT_EQ(crs.code, "EPSG:32631");
  EXPECT_TRUE(same_as_epsg(crs.wkt, 32631));
}

TEST(Crs, AWrongCodeIsRefusedWithTheText) {
  const std::string wrong = invalid_message("EPSG:999999");
  EXPECT_NE(wrong.find("'EPSG:999999' is not a coordinate reference system GDAL knows"), std::string::npos) << wrong;
  EXPECT_NE(invalid_message("ED50 UTM 31").find("'ED50 UTM 31'"), std::string::npos);
  EXPECT_NE(invalid_message("").find("empty"), std::string::npos);
  // Degrees are not map coordinates.
  const std::string geographic = invalid_message("EPSG:4326");
  EXPECT_NE(geographic.find("geographic"), std::string::npos) << geographic;
  // No file is read through the CRS's text.
  EXPECT_NE(invalid_message("/etc/passwd").find("'/etc/passwd'"), std::string::npos);
}

TEST(Crs, ReadFromACfNetcdfWrittenWithGdal) {
  ScratchDir dir;
  const std::string path = dir.file("cf.nc");
  write_foreign(path, "netCDF", [&](GDALGroup& root) {
    std::vector<std::shared_ptr<GDALDimension>> dims{root.CreateDimension("iline", "HORIZONTAL_Y", "", 6),
                                                     root.CreateDimension("xline", "HORIZONTAL_X", "", 5),
                                                     root.CreateDimension("twt", "VERTICAL", "", 7)};
    write_coordinate(root, dims[0], 100, 1, nullptr);
    write_coordinate(root, dims[1], 200, 1, nullptr);
    write_coordinate(root, dims[2], 0, 4, "ms");
    auto array = add_array(root, "seismic", dims, GDT_Float32);
    OGRSpatialReference srs;
    ASSERT_EQ(srs.importFromEPSG(23031), OGRERR_NONE);
    ASSERT_TRUE(array->SetSpatialRef(&srs)); // a CF grid_mapping variable, as GDAL writes it
    fill_array(*array, {0, 1, 2});
  });
  auto cube = gv::open_volume(path);
  EXPECT_EQ(cube->geometry().crs.code, "EPSG:23031");
  EXPECT_EQ(cube->geometry().crs.name, "ED50 / UTM zone 31N");
  EXPECT_TRUE(same_as_epsg(cube->geometry().crs.wkt, 23031));
  expect_formula(cube->read(cube->geometry().bounds()), cube->geometry().bounds());
}

// A Zarr store as xarray writes one: each dimension named (_ARRAY_DIMENSIONS) with its coordinate
// array, the sample axis's `units` as given, the CRS as a `crs` attribute. GDAL 3.6's Zarr writer
// names an array's dimensions only when every one has an indexing variable; without that the file
// says nothing of the sample axis (its dimensions read back as dim0, dim1, dim2).
std::unique_ptr<gv::Volume> zarr_with_sample_axis(const std::string& path, const char* axis, double first, double step,
                                                  const char* unit) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("Zarr");
  EXPECT_NE(driver, nullptr);
  if (!driver) return nullptr;
  GDALDataset* dataset = driver->CreateMultiDimensional(path.c_str(), nullptr, nullptr);
  EXPECT_NE(dataset, nullptr);
  if (!dataset) return nullptr;
  {
    auto root = dataset->GetRootGroup();
    std::vector<std::shared_ptr<GDALDimension>> dims{root->CreateDimension("iline", "", "", 4),
                                                     root->CreateDimension("xline", "", "", 3),
                                                     root->CreateDimension(axis, "", "", 5)};
    write_coordinate(*root, dims[0], 100, 1, nullptr);
    write_coordinate(*root, dims[1], 200, 1, nullptr);
    write_coordinate(*root, dims[2], first, step, unit);
    for (auto& dim : dims)
      EXPECT_TRUE(dim->SetIndexingVariable(root->OpenMDArray(dim->GetName())));
    auto array = add_array(*root, "seismic", dims, GDT_Float32);
    array->CreateAttribute("crs", {}, GDALExtendedDataType::CreateString())->Write("EPSG:2227");
    fill_array(*array, {0, 1, 2});
  }
  GDALClose(GDALDataset::ToHandle(dataset));
  return gv::open_volume(path);
}

TEST(Crs, ReadFromACrsAttributeOfAZarrArray) {
  ScratchDir dir;
  auto cube = zarr_with_sample_axis(dir.file("attr.zarr"), "depth", 1000, 10, "ft");
  ASSERT_NE(cube, nullptr);
  EXPECT_EQ(cube->geometry().crs.code, "EPSG:2227");
  EXPECT_EQ(cube->geometry().crs.unit, "ftUS");
  EXPECT_EQ(cube->geometry().inline0, 100);
  EXPECT_EQ(cube->geometry().crossline0, 200);
  // Depth in feet as the file says, not metres nor milliseconds.
  EXPECT_EQ(cube->geometry().z_unit, gv::SampleUnit::feet);
  EXPECT_EQ(cube->geometry().z0, 1000);
  EXPECT_EQ(cube->geometry().dz, 10);
  EXPECT_EQ(gv::volume_unit(cube->geometry()), "ftUS^2*ft");
  expect_formula(cube->read(cube->geometry().bounds()), cube->geometry().bounds());
}

TEST(Crs, ASampleAxisInSecondsIsReadAsMilliseconds) {
  ScratchDir dir;
  auto cube = zarr_with_sample_axis(dir.file("seconds.zarr"), "twt", 0.5, 0.004, "s");
  ASSERT_NE(cube, nullptr);
  EXPECT_EQ(cube->geometry().z_unit, gv::SampleUnit::milliseconds);
  EXPECT_NEAR(cube->geometry().z0, 500.0, 1e-9);
  EXPECT_NEAR(cube->geometry().dz, 4.0, 1e-9);
  EXPECT_EQ(gv::volume_unit(cube->geometry()), "ftUS^2*ms");
}

TEST(Crs, AnUnknownCrsInAFileIsAFormatErrorUnlessOneIsGiven) {
  ScratchDir dir;
  const std::string path = dir.file("bad.nc");
  write_foreign(path, "netCDF", [&](GDALGroup& root) {
    std::vector<std::shared_ptr<GDALDimension>> dims{root.CreateDimension("iline", "", "", 4),
                                                     root.CreateDimension("xline", "", "", 3),
                                                     root.CreateDimension("twt", "", "", 5)};
    auto array = add_array(root, "seismic", dims, GDT_Float32);
    array->CreateAttribute("crs", {}, GDALExtendedDataType::CreateString())->Write("EPSG:999999");
    fill_array(*array, {0, 1, 2});
  });
  const std::string message = message_of([&] { gv::open_volume(path); });
  EXPECT_NE(message.find("attribute crs of array /seismic"), std::string::npos) << message;
  gv::OpenOptions options;
  options.crs = gv::parse_crs("EPSG:23031");
  EXPECT_EQ(gv::open_volume(path, options)->geometry().crs.code, "EPSG:23031");
}

TEST(Crs, ReadFromAGeoTiffTimeSliceStack) {
  ScratchDir dir;
  const std::string path = dir.file("slices.tif");
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  GDALDataset* dataset = driver->Create(path.c_str(), 6, 5, 4, GDT_Float32, nullptr);
  ASSERT_NE(dataset, nullptr);
  double transform[6] = {431000.0, 25.0, 0.0, 4612000.0, 0.0, -25.0};
  dataset->SetGeoTransform(transform);
  OGRSpatialReference srs;
  ASSERT_EQ(srs.importFromEPSG(23031), OGRERR_NONE);
  dataset->SetSpatialRef(&srs);
  std::vector<float> band(30, 1.0f);
  for (int b = 1; b <= 4; ++b)
    ASSERT_EQ(dataset->GetRasterBand(b)->RasterIO(GF_Write, 0, 0, 6, 5, band.data(), 6, 5, GDT_Float32, 0, 0, nullptr),
              CE_None);
  GDALClose(GDALDataset::ToHandle(dataset));
  auto cube = gv::open_volume(path);
  EXPECT_EQ(cube->geometry().crs.code, "EPSG:23031");
  EXPECT_TRUE(same_as_epsg(cube->geometry().crs.wkt, 23031));
}

// Every writer geotandem has but SEG-Y's keeps the CRS, and reads it back the same.
TEST(Crs, WrittenCubesKeepTheirCrs) {
  ScratchDir dir;
  gv::Geometry g = test_geometry({5, 4, 6});
  g.crs = gv::parse_crs("EPSG:23031");
  auto cube = make_cube(g);
  for (const char* name : {"cube.nc", "cube.zarr", "cube.tif", "cube.raw"}) {
    SCOPED_TRACE(name);
    gv::write_volume(*cube, dir.file(name));
    auto back = gv::open_volume(dir.file(name));
    EXPECT_EQ(back->geometry().crs, g.crs);
    EXPECT_TRUE(back->geometry().same_grid(g));
  }
  // Without one, none is invented.
  auto plain = make_cube(test_geometry({5, 4, 6}));
  gv::write_volume(*plain, dir.file("plain.nc"));
  EXPECT_TRUE(gv::open_volume(dir.file("plain.nc"))->geometry().crs.empty());
  EXPECT_EQ(gv::open_volume(dir.file("plain.nc"))->geometry().crs.label(), "no CRS given");
}

TEST(Crs, AGivenCrsReplacesTheFilesAndSaysSo) {
  ScratchDir dir;
  gv::Geometry g = test_geometry({5, 4, 6});
  g.crs = gv::parse_crs("EPSG:23031");
  gv::write_volume(*make_cube(g), dir.file("cube.nc"));
  gv::OpenOptions options;
  options.crs = gv::parse_crs("EPSG:23032");
  auto cube = gv::open_volume(dir.file("cube.nc"), options);
  EXPECT_EQ(cube->geometry().crs.code, "EPSG:23032");
  const auto warnings = gv::open_warnings(*cube);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("the file says the CRS is ED50 / UTM zone 31N (EPSG:23031)"), std::string::npos)
      << warnings[0];
  expect_formula(cube->read(cube->geometry().bounds()), cube->geometry().bounds());
}

} // namespace
