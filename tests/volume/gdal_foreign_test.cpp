// GDAL-backed formats as other tools leave them: files written through GDAL directly (coordinate
// variables, other dimension orders, HDF5), arrays that are not cubes, broken files, and MEM
// datasets handed over without a file. Coordinates that are uneven or skip lines:
// gdal_coordinates_test.cpp.

#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <ostream>
#include <random>
#include <thread>

#include "gdal_fixtures.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/volume/io.hpp"
#include "scratch.hpp"

namespace {

namespace fs = std::filesystem;
namespace gv = geotandem::volume;
using geotandem::testing::ScratchDir;
using namespace gdal_fixtures;

// ---- files from other tools -------------------------------------------------------------------

TEST(GdalMdForeign, CoordinateVariablesGiveGeometryWithoutAttributes) {
  ScratchDir dir;
  const std::string path = dir.file("foreign.nc");
  write_foreign(path, "netCDF", [](GDALGroup& root) {
    auto il = root.CreateDimension("iline", "", "", 6);
    auto xl = root.CreateDimension("xline", "", "", 7);
    auto tw = root.CreateDimension("twt", "", "", 8);
    write_coordinate(root, il, 500, 2, nullptr);
    write_coordinate(root, tw, 0.008, 0.0025, "s"); // seconds: read as 8 ms, 2.5 ms
    fill_array(*add_array(root, "seismic", {il, xl, tw}, GDT_Float64), {0, 1, 2});
  });
  const auto cube = gv::open_volume(path);
  const gv::Geometry& g = cube->geometry();
  EXPECT_EQ(g.shape, (gv::Index3{6, 7, 8}));
  EXPECT_EQ(g.inline0, 500);
  EXPECT_EQ(g.inline_step, 2);
  EXPECT_EQ(g.crossline0, 0) << "no coordinate variable: indices are the line numbers";
  EXPECT_EQ(g.crossline_step, 1);
  EXPECT_DOUBLE_EQ(g.z0, 8);
  EXPECT_DOUBLE_EQ(g.dz, 2.5);
  EXPECT_EQ(g.z_unit, gv::SampleUnit::milliseconds);
  EXPECT_EQ(g.affine, gv::SurveyAffine{});
  expect_formula(cube->read(g.bounds()), g.bounds());
}

TEST(GdalMdForeign, NamedDimensionsInAnotherOrderAreTransposed) {
  ScratchDir dir;
  const std::string path = dir.file("transposed.nc");
  // Stored as [depth, xline, iline]: cube axes 2, 1, 0.
  write_foreign(path, "netCDF", [](GDALGroup& root) {
    auto z = root.CreateDimension("depth", "", "", 9);
    auto xl = root.CreateDimension("xline", "", "", 5);
    auto il = root.CreateDimension("iline", "", "", 4);
    fill_array(*add_array(root, "velocity", {z, xl, il}, GDT_Float32), {2, 1, 0});
  });
  const auto cube = gv::open_volume(path);
  const gv::Geometry& g = cube->geometry();
  EXPECT_EQ(g.shape, (gv::Index3{4, 5, 9}));
  EXPECT_EQ(g.z_unit, gv::SampleUnit::metres) << "a dimension named depth is in metres";
  expect_formula(cube->read(g.bounds()), g.bounds());
  expect_formula(cube->read({{1, 2, 3}, {3, 5, 8}}), {{1, 2, 3}, {3, 5, 8}});
}

// CF files put time or depth first: stored as [time, y, x], the cube is read with x as the inline
// and y as the crossline axis (east and north in the default affine). A sample axis named as such
// but stored first among names that say nothing is refused: read in stored order it made every
// trace a line.
TEST(GdalMdForeign, ASampleAxisStoredFirstIsReadByItsName) {
  ScratchDir dir;
  const std::string path = dir.file("cf.nc");
  write_foreign(path, "netCDF", [](GDALGroup& root) {
    auto t = root.CreateDimension("time", "", "", 9);
    auto y = root.CreateDimension("y", "", "", 5);
    auto x = root.CreateDimension("x", "", "", 4);
    write_coordinate(root, x, 431000, 25, "m");
    fill_array(*add_array(root, "amplitude", {t, y, x}, GDT_Float32), {2, 1, 0});
  });
  const auto cube = gv::open_volume(path);
  const gv::Geometry& g = cube->geometry();
  EXPECT_EQ(g.shape, (gv::Index3{4, 5, 9}));
  EXPECT_EQ(g.inline0, 431000);
  EXPECT_EQ(g.inline_step, 25);
  expect_formula(cube->read(g.bounds()), g.bounds());

  const std::string unnamed = dir.file("unnamed.nc");
  write_foreign(unnamed, "netCDF", [](GDALGroup& root) {
    auto t = root.CreateDimension("time", "", "", 9);
    auto a = root.CreateDimension("a", "", "", 5);
    auto b = root.CreateDimension("b", "", "", 4);
    fill_array(*add_array(root, "amplitude", {t, a, b}, GDT_Float32), {2, 1, 0});
  });
  const std::string message = message_of([&] { gv::open_volume(unnamed); });
  EXPECT_NE(message.find("dimension 'time' of array /amplitude is the sample axis by its name, stored as axis 1 of 3"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("(a, b)"), std::string::npos) << message;
  EXPECT_NE(message.find("unnamed.nc"), std::string::npos) << message;
}

// netCDF's _FillValue and Zarr's fill_value (what GDAL reports as an array's no-data value, set here
// through GDAL as other tools set them) mark samples as missing, as NaN samples are.
TEST(GdalMdForeign, FillValueSamplesAreMissing) {
  ScratchDir dir;
  const gv::Index3 missing{1, 4, 2};
  const double no_data = value_at(missing[0], missing[1], missing[2]);
  for (const char* driver : {"netCDF", "Zarr"}) {
    const std::string path = dir.file(std::string(driver) == "Zarr" ? "filled.zarr" : "filled.nc");
    GDALAllRegister();
    GDALDriver* gdal_driver = GetGDALDriverManager()->GetDriverByName(driver);
    ASSERT_NE(gdal_driver, nullptr) << driver;
    GDALDataset* dataset = gdal_driver->CreateMultiDimensional(path.c_str(), nullptr, nullptr);
    ASSERT_NE(dataset, nullptr) << driver;
    {
      auto root = dataset->GetRootGroup();
      auto il = root->CreateDimension("iline", "", "", 3);
      auto xl = root->CreateDimension("xline", "", "", 6);
      auto tw = root->CreateDimension("twt", "", "", 5);
      auto array = add_array(*root, "seismic", {il, xl, tw}, GDT_Float32);
      ASSERT_TRUE(array->SetNoDataValue(no_data)) << driver;
      fill_array(*array, {0, 1, 2});
    }
    GDALClose(GDALDataset::ToHandle(dataset));

    gv::OpenOptions fill;
    fill.nan_policy = gv::NanPolicy::fill;
    const auto cube = gv::open_volume(path, fill);
    const gv::Box all = cube->geometry().bounds();
    const std::vector<float> samples = cube->read(all);
    for (std::int64_t i = 0; i < 3; ++i)
      for (std::int64_t j = 0; j < 6; ++j)
        for (std::int64_t k = 0; k < 5; ++k)
          ASSERT_EQ(samples[all.offset({i, j, k})],
                    (gv::Index3{i, j, k} == missing ? std::numeric_limits<float>::lowest() : value_at(i, j, k)))
              << driver << " " << i << ", " << j << ", " << k;
    bool listed = false;
    for (const auto& d : cube->format_details())
      listed = listed || d.key == gv::kNoDataDetail;
    EXPECT_TRUE(listed) << driver;
    EXPECT_THROW(gv::open_volume(path)->read(all), geotandem::DataError) << driver;
    // A box without the missing sample reads as it always did.
    expect_formula(gv::open_volume(path)->read({{0, 0, 0}, {1, 6, 5}}), {{0, 0, 0}, {1, 6, 5}});
  }
}

TEST(GdalMdForeign, Hdf5CopyOfANetcdfFileOpensAsHdf5) {
  ScratchDir dir;
  const auto source = make_cube(test_geometry({12, 10, 21}));
  const std::string nc = dir.file("cube.nc"), h5 = dir.file("cube.h5");
  gv::write_volume(*source, nc, {.chunk = 8});
  fs::copy_file(nc, h5);
  EXPECT_EQ(gv::detect_format(h5), "HDF5");
  const auto cube = gv::open_volume(h5);
  EXPECT_EQ(cube->format(), "HDF5");
  EXPECT_EQ(cube->geometry(), source->geometry());
  expect_formula(cube->read(cube->geometry().bounds()), cube->geometry().bounds());
  expect_formula(cube->read({{3, 7, 5}, {11, 10, 17}}), {{3, 7, 5}, {11, 10, 17}});
}

// ---- arrays that are not cubes, and broken files ----------------------------------------------

TEST(GdalMdErrors, NonFloatAndTwoDimensionalArraysAreNamed) {
  ScratchDir dir;
  const std::string path = dir.file("not_cubes.nc");
  write_foreign(path, "netCDF", [](GDALGroup& root) {
    auto il = root.CreateDimension("iline", "", "", 3);
    auto xl = root.CreateDimension("xline", "", "", 4);
    auto tw = root.CreateDimension("twt", "", "", 5);
    add_array(root, "counts", {il, xl, tw}, GDT_Int16);
    add_array(root, "horizon", {il, xl}, GDT_Float32);
  });
  std::string none = message_of([&] { gv::open_volume(path); });
  EXPECT_NE(none.find(path), std::string::npos) << none;
  EXPECT_NE(none.find("no 3-D"), std::string::npos) << none;
  EXPECT_NE(none.find("counts (Int16, 3x4x5)"), std::string::npos) << none;
  EXPECT_NE(none.find("horizon (Float32, 3x4)"), std::string::npos) << none;

  std::string integer = message_of([&] { gv::open_volume(path, {.variable = "counts"}); });
  EXPECT_NE(integer.find("Int16"), std::string::npos) << integer;
  EXPECT_NE(integer.find("floating-point"), std::string::npos) << integer;

  std::string flat = message_of([&] { gv::open_volume(path, {.variable = "horizon"}); });
  EXPECT_NE(flat.find("has 2 dimensions"), std::string::npos) << flat;
}

TEST(GdalMdErrors, VariableChoiceListsTheCandidates) {
  ScratchDir dir;
  const std::string path = dir.file("two_cubes.nc");
  write_foreign(path, "netCDF", [](GDALGroup& root) {
    auto il = root.CreateDimension("iline", "", "", 3);
    auto xl = root.CreateDimension("xline", "", "", 4);
    auto tw = root.CreateDimension("twt", "", "", 5);
    add_array(root, "envelope", {il, xl, tw}, GDT_Float32);
    fill_array(*add_array(root, "chaos", {il, xl, tw}, GDT_Float32), {0, 1, 2});
  });
  std::string several = message_of([&] { gv::open_volume(path); });
  EXPECT_NE(several.find("several"), std::string::npos) << several;
  EXPECT_NE(several.find("envelope"), std::string::npos) << several;
  EXPECT_NE(several.find("chaos"), std::string::npos) << several;
  EXPECT_NE(several.find("--variable"), std::string::npos) << several;

  std::string missing = message_of([&] { gv::open_volume(path, {.variable = "semblance"}); });
  EXPECT_NE(missing.find("'semblance'"), std::string::npos) << missing;
  EXPECT_NE(missing.find("envelope (Float32, 3x4x5)"), std::string::npos) << missing;
  EXPECT_NE(missing.find("chaos (Float32, 3x4x5)"), std::string::npos) << missing;

  const auto cube = gv::open_volume(path, {.variable = "chaos"});
  expect_formula(cube->read(cube->geometry().bounds()), cube->geometry().bounds());
}

TEST(GdalMdErrors, TruncatedNetcdfIsAFormatErrorNamingTheFile) {
  ScratchDir dir;
  const auto source = make_cube(test_geometry({37, 29, 53}));
  const std::string path = dir.file("truncated.nc");
  gv::write_volume(*source, path, {.chunk = 16});
  fs::resize_file(path, fs::file_size(path) / 2);
  std::string text = message_of([&] {
    auto cube = gv::open_volume(path);
    cube->read(cube->geometry().bounds());
  });
  EXPECT_NE(text.find(path), std::string::npos) << text;

  const std::string garbage = dir.file("garbage.nc");
  {
    std::ofstream out(garbage, std::ios::binary);
    out << "\x89HDF\r\n\x1a\n" << std::string(4000, 'x');
  }
  std::string bad = message_of([&] { gv::open_volume(garbage); });
  EXPECT_NE(bad.find(garbage), std::string::npos) << bad;
  EXPECT_NE(bad.find("netCDF"), std::string::npos) << bad;
}

TEST(GdalRasterErrors, IntegerGeotiffIsAFormatError) {
  ScratchDir dir;
  const std::string path = dir.file("bytes.tif");
  GDALAllRegister();
  GDALDataset* dataset =
      GetGDALDriverManager()->GetDriverByName("GTiff")->Create(path.c_str(), 8, 8, 2, GDT_Byte, nullptr);
  ASSERT_NE(dataset, nullptr);
  GDALClose(GDALDataset::ToHandle(dataset));
  std::string text = message_of([&] { gv::open_volume(path); });
  EXPECT_NE(text.find("Byte"), std::string::npos) << text;
  EXPECT_NE(text.find(path), std::string::npos) << text;
}

} // namespace

// ---- MEM: a dataset handed over without a file --------------------------------------------------

namespace {

// A MEM multidimensional dataset with one (inline, crossline, time) Float32 array of value
// 1000 i + 10 j + k, the time axis in seconds with a coordinate variable, and `bad` NaN samples.
GDALDataset* make_mem_cube(int bad) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("MEM");
  if (!driver) return nullptr;
  GDALDataset* dataset = driver->CreateMultiDimensional("in-memory", nullptr, nullptr);
  auto root = dataset->GetRootGroup();
  auto il = root->CreateDimension("inline", "", "", 5);
  auto xl = root->CreateDimension("crossline", "", "", 4);
  auto t = root->CreateDimension("time", "", "", 6);
  auto time = root->CreateMDArray("time", {t}, GDALExtendedDataType::Create(GDT_Float64));
  time->SetUnit("s");
  std::vector<double> seconds = {0.1, 0.104, 0.108, 0.112, 0.116, 0.12};
  const GUInt64 start0 = 0;
  const std::size_t count0 = seconds.size();
  time->Write(&start0, &count0, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float64), seconds.data());
  t->SetIndexingVariable(time);
  auto array = root->CreateMDArray("amplitude", {il, xl, t}, GDALExtendedDataType::Create(GDT_Float32));
  std::vector<float> values(5 * 4 * 6);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 6; ++k)
        values[static_cast<std::size_t>((i * 4 + j) * 6 + k)] = static_cast<float>(1000 * i + 10 * j + k);
  for (int n = 0; n < bad; ++n)
    values[static_cast<std::size_t>(7 + n)] = std::numeric_limits<float>::quiet_NaN();
  const GUInt64 start[3] = {0, 0, 0};
  const std::size_t count[3] = {5, 4, 6};
  array->Write(start, count, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float32), values.data());
  return dataset;
}

} // namespace

TEST(GdalMem, AnInMemoryDatasetIsACubeLikeAFile) {
  GDALDataset* dataset = make_mem_cube(0);
  ASSERT_NE(dataset, nullptr) << "GDAL has no MEM driver";
  auto cube = gv::open_gdal_dataset(dataset, "in-memory cube");
  EXPECT_EQ(cube->format(), "MEM");
  EXPECT_EQ(cube->source(), "in-memory cube");
  const auto& g = cube->geometry();
  EXPECT_EQ(g.shape[0], 5);
  EXPECT_EQ(g.shape[1], 4);
  EXPECT_EQ(g.shape[2], 6);
  EXPECT_NEAR(g.z0, 100.0, 1e-9); // seconds became milliseconds
  EXPECT_NEAR(g.dz, 4.0, 1e-9);
  gv::Box box{{1, 2, 3}, {4, 4, 6}};
  auto samples = cube->read(box);
  std::size_t n = 0;
  for (int i = 1; i < 4; ++i)
    for (int j = 2; j < 4; ++j)
      for (int k = 3; k < 6; ++k)
        EXPECT_EQ(samples[n++], static_cast<float>(1000 * i + 10 * j + k)) << i << ' ' << j << ' ' << k;
}

TEST(GdalMem, NanPolicyAppliesToDatasetsToo) {
  GDALDataset* dataset = make_mem_cube(2);
  ASSERT_NE(dataset, nullptr);
  auto cube = gv::open_gdal_dataset(dataset, "in-memory cube");
  try {
    cube->read(cube->geometry().bounds());
    FAIL() << "NaN samples were read without an error";
  } catch (const geotandem::DataError& e) {
    EXPECT_NE(std::string(e.what()).find("in-memory cube"), std::string::npos) << e.what();
  }
  EXPECT_THROW(gv::open_gdal_dataset(nullptr, "nothing"), geotandem::InvalidArgument);
}
