// Classic rasters (GeoTIFF, ENVI) as other tools write them: time-slice stacks, band b = sample
// b - 1, raster x/y = inline/crossline, the geotransform giving the survey affine; written here
// through GDAL directly, not through geotandem's writer. And GeoTIFFs geotandem wrote (inline
// slices), with and without the layout item, reading as they always did.

#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "gdal_fixtures.hpp"
#include "scratch.hpp"

namespace {

namespace gv = geotandem::volume;
using geotandem::testing::ScratchDir;
using namespace gdal_fixtures;

// A time-slice stack of `shape` = (inlines = raster width, crosslines = raster height, samples =
// bands) holding value_at(i, j, k) at pixel (i, j) of band k + 1, with `transform` unless null.
void write_time_slices(const std::string& path, const char* driver_name, gv::Index3 shape,
                       const std::array<double, 6>* transform, GDALDataType type = GDT_Float32,
                       std::optional<double> no_data = std::nullopt) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driver_name);
  ASSERT_NE(driver, nullptr);
  const auto nx = static_cast<int>(shape[0]), ny = static_cast<int>(shape[1]), bands = static_cast<int>(shape[2]);
  GDALDataset* dataset = driver->Create(path.c_str(), nx, ny, bands, type, nullptr);
  ASSERT_NE(dataset, nullptr);
  if (transform) {
    std::array<double, 6> t = *transform;
    ASSERT_EQ(dataset->SetGeoTransform(t.data()), CE_None);
  }
  std::vector<float> slice(static_cast<std::size_t>(nx * ny));
  for (int b = 1; b <= bands; ++b) {
    if (no_data) {
      ASSERT_EQ(dataset->GetRasterBand(b)->SetNoDataValue(*no_data), CE_None);
    }
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x)
        slice[static_cast<std::size_t>(y * nx + x)] = value_at(x, y, b - 1);
    ASSERT_EQ(
        dataset->GetRasterBand(b)->RasterIO(GF_Write, 0, 0, nx, ny, slice.data(), nx, ny, GDT_Float32, 0, 0, nullptr),
        CE_None);
  }
  GDALClose(GDALDataset::ToHandle(dataset));
}

std::string detail_of(const gv::Volume& v, const std::string& key) {
  for (const auto& d : v.format_details())
    if (d.key == key) return d.value;
  return "(none)";
}

std::string layout_detail(const gv::Volume& v) {
  return detail_of(v, "layout");
}

void expect_boxes(const gv::Volume& cube) {
  const gv::Index3 s = cube.geometry().shape;
  expect_formula(cube.read(cube.geometry().bounds()), cube.geometry().bounds());
  for (const gv::Box& box :
       {gv::Box{{1, 2, 3}, {s[0] - 1, s[1], s[2] - 1}}, gv::Box{{s[0] - 1, 0, 0}, s}, gv::Box{{0, 1, 2}, {1, 2, 3}}})
    expect_formula(cube.read(box), box);
}

TEST(GdalTimeSlices, GeotiffStackWithAGeotransformReadsAsMapSlices) {
  ScratchDir dir;
  const std::string path = dir.file("slices.tif");
  // A rotated grid: 12.5 m along raster x, 25 m along raster y, 20 degrees off north.
  const double c = std::cos(0.349), s = std::sin(0.349);
  const std::array<double, 6> transform{612000.0, 12.5 * c, -25.0 * s, 6702000.0, -12.5 * s, -25.0 * c};
  const gv::Index3 shape{11, 7, 9}; // 11 inlines (x), 7 crosslines (y), 9 time slices (bands)
  write_time_slices(path, "GTiff", shape, &transform);

  EXPECT_EQ(gv::detect_format(path), "GeoTIFF");
  const auto cube = gv::open_volume(path);
  const gv::Geometry& g = cube->geometry();
  EXPECT_EQ(g.shape, shape);
  EXPECT_EQ(g.inline0, 0);
  EXPECT_EQ(g.crossline0, 0);
  EXPECT_EQ(g.dz, gv::Geometry{}.dz);
  EXPECT_NE(layout_detail(*cube).find("time slices"), std::string::npos) << layout_detail(*cube);
  // Every trace sits at its pixel's centre, as GDAL itself maps it.
  for (int i : {0, 4, 10})
    for (int j : {0, 6}) {
      double x = 0, y = 0;
      GDALApplyGeoTransform(const_cast<double*>(transform.data()), i + 0.5, j + 0.5, &x, &y);
      const auto w = g.world(i, j, 3);
      EXPECT_NEAR(w[0], x, 1e-6) << i << "," << j;
      EXPECT_NEAR(w[1], y, 1e-6) << i << "," << j;
    }
  EXPECT_NEAR(g.affine.step_i(), 12.5, 1e-9);
  EXPECT_NEAR(g.affine.step_j(), 25.0, 1e-9);
  expect_boxes(*cube);

  // The file places the survey but not the sample axis: the default is said, and how to set it.
  const std::string assumed = detail_of(*cube, "assumed");
  EXPECT_EQ(assumed.rfind("the sample axis, 0 ms at steps of 4 ms (set the metadata items geotandem_z0", 0), 0)
      << assumed;
  EXPECT_EQ(assumed.find("position"), std::string::npos) << assumed;
  const auto warnings = gv::open_warnings(*cube);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], path + ": not in the file, assumed: " + assumed);
  { // Once the file says its sample interval, nothing is assumed.
    GDALDataset* dataset = GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE);
    ASSERT_NE(dataset, nullptr);
    ASSERT_EQ(dataset->SetMetadataItem("geotandem_dz", "2"), CE_None);
    GDALClose(GDALDataset::ToHandle(dataset));
  }
  const auto told = gv::open_volume(path);
  EXPECT_EQ(told->geometry().dz, 2.0);
  EXPECT_EQ(detail_of(*told, "assumed"), "(none)");
  EXPECT_TRUE(gv::open_warnings(*told).empty());
}

TEST(GdalTimeSlices, StackWithoutGeotransformGetsTheDefaultGrid) {
  ScratchDir dir;
  for (const char* driver : {"GTiff", "ENVI"}) {
    const std::string path = dir.file(std::string("plain_") + driver + (driver[0] == 'G' ? ".tif" : ".bin"));
    write_time_slices(path, driver, {6, 9, 11}, nullptr);
    const auto cube = gv::open_volume(path);
    EXPECT_EQ(cube->format(), driver[0] == 'G' ? "GeoTIFF" : "ENVI");
    EXPECT_EQ(cube->geometry().shape, (gv::Index3{6, 9, 11}));
    EXPECT_EQ(cube->geometry().affine, gv::SurveyAffine{});
    expect_boxes(*cube);
    const std::string assumed = detail_of(*cube, "assumed");
    EXPECT_NE(assumed.find("the sample axis, 0 ms at steps of 4 ms"), std::string::npos) << assumed;
    EXPECT_NE(assumed.find("; the survey's position, bins of 25 m from x 0, y 0 (the file has no geotransform"),
              std::string::npos)
        << assumed;
  }
}

TEST(GdalTimeSlices, DegenerateGeotransformIsAFormatError) {
  ScratchDir dir;
  const std::string path = dir.file("flat.tif");
  const std::array<double, 6> transform{0, 10, 20, 0, 10, 20}; // x and y map to the same direction
  write_time_slices(path, "GTiff", {4, 4, 3}, &transform);
  const std::string text = message_of([&] { gv::open_volume(path); });
  EXPECT_NE(text.find("degenerate"), std::string::npos) << text;
  EXPECT_NE(text.find("geotransform"), std::string::npos) << text;
  EXPECT_NE(text.find(path), std::string::npos) << text;
}

// ---- GeoTIFFs geotandem wrote: inline slices ----------------------------------------------------

TEST(GdalInlineSlices, GeotandemGeotiffIsMarkedAndReadsAsBefore) {
  ScratchDir dir;
  const auto source = make_cube(test_geometry({13, 8, 21}));
  const std::string path = dir.file("ours.tif");
  gv::write_volume(*source, path, {.chunk = 16});
  {
    // Bands are inlines, the item says so, and there is no geotransform to take for a map.
    GDALAllRegister();
    GDALDataset* d = GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(d->GetRasterCount(), 13);
    EXPECT_EQ(d->GetRasterXSize(), 21);
    EXPECT_STREQ(d->GetMetadataItem("geotandem_layout"), "inline_slices");
    GDALClose(GDALDataset::ToHandle(d));
  }
  const auto cube = gv::open_volume(path);
  EXPECT_EQ(cube->geometry(), source->geometry());
  EXPECT_NE(layout_detail(*cube).find("inline slices"), std::string::npos) << layout_detail(*cube);
  expect_boxes(*cube);
}

TEST(GdalInlineSlices, OlderGeotandemGeotiffWithoutTheItemStillReadsAsInlineSlices) {
  ScratchDir dir;
  const auto source = make_cube(test_geometry({13, 8, 21}));
  const std::string path = dir.file("older.tif");
  gv::write_volume(*source, path, {.chunk = 16});
  {
    GDALDataset* d = GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE);
    ASSERT_NE(d, nullptr);
    ASSERT_EQ(d->SetMetadataItem("geotandem_layout", nullptr), CE_None);
    GDALClose(GDALDataset::ToHandle(d));
    d = GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
    ASSERT_NE(d, nullptr);
    ASSERT_EQ(d->GetMetadataItem("geotandem_layout"), nullptr) << "the item should be gone";
    ASSERT_NE(d->GetMetadataItem("geotandem_inline0"), nullptr);
    GDALClose(GDALDataset::ToHandle(d));
  }
  const auto cube = gv::open_volume(path);
  EXPECT_EQ(cube->geometry(), source->geometry());
  expect_boxes(*cube);
}

TEST(GdalInlineSlices, UnknownLayoutItemIsAFormatError) {
  ScratchDir dir;
  const std::string path = dir.file("odd.tif");
  write_time_slices(path, "GTiff", {4, 4, 3}, nullptr);
  {
    GDALDataset* d = GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE);
    ASSERT_NE(d, nullptr);
    d->SetMetadataItem("geotandem_layout", "crossline_slices");
    GDALClose(GDALDataset::ToHandle(d));
  }
  const std::string text = message_of([&] { gv::open_volume(path); });
  EXPECT_NE(text.find("crossline_slices"), std::string::npos) << text;
  EXPECT_NE(text.find("time_slices"), std::string::npos) << text;
}

} // namespace

namespace {

// The whole cube read back: the sample at `missing` reads as `fill`, every other one as the formula.
void expect_missing_at(const gv::Volume& cube, gv::Index3 missing, float fill) {
  const gv::Box all = cube.geometry().bounds();
  const std::vector<float> samples = cube.read(all);
  for (std::int64_t i = 0; i < all.hi[0]; ++i)
    for (std::int64_t j = 0; j < all.hi[1]; ++j)
      for (std::int64_t k = 0; k < all.hi[2]; ++k) {
        const float want = gv::Index3{i, j, k} == missing ? fill : value_at(i, j, k);
        ASSERT_EQ(samples[all.offset({i, j, k})], want) << i << ", " << j << ", " << k;
      }
}

} // namespace

// A no-data value declared by the file (GeoTIFF's nodata tag, ENVI's "data ignore value", set here
// through GDAL as other tools set them) marks samples as missing: an error naming the sample and the
// value by default, outside every body with the fill. Read as a value, -999.25 would be an amplitude.
TEST(GdalNoData, DeclaredNoDataSamplesAreMissing) {
  ScratchDir dir;
  for (const char* driver : {"GTiff", "ENVI"}) {
    const std::string path =
        dir.file(std::string("nodata_") + driver + (std::string(driver) == "GTiff" ? ".tif" : ".img"));
    const gv::Index3 shape{5, 6, 7}, missing{2, 3, 4};
    // Declared when the file is made. (Opening it again in update mode to set the value, as
    // gdal_edit does, made LeakSanitizer's tracer crash at this test's exit under the address
    // sanitizer, after the test had passed.)
    write_time_slices(path, driver, shape, nullptr, GDT_Float32, value_at(missing[0], missing[1], missing[2]));
    gv::OpenOptions fill;
    fill.nan_policy = gv::NanPolicy::fill;
    const auto cube = gv::open_volume(path, fill);
    bool listed = false;
    for (const auto& d : cube->format_details())
      listed = listed || (d.key == gv::kNoDataDetail && d.value.rfind("20304.5 ", 0) == 0);
    EXPECT_TRUE(listed) << driver << ": the no-data value is not among the format details";
    expect_missing_at(*cube, missing, std::numeric_limits<float>::lowest());
    try {
      gv::open_volume(path)->read(cube->geometry().bounds());
      FAIL() << driver << ": a no-data sample was read as an amplitude";
    } catch (const geotandem::DataError& e) {
      const std::string text = e.what();
      EXPECT_NE(text.find("(2, 3, 4)"), std::string::npos) << text;
      EXPECT_NE(text.find("declares 20304.5 as no data"), std::string::npos) << text;
    }
  }
}
