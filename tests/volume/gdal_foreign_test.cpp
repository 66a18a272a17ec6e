// GDAL-backed formats as other tools leave them: files written through GDAL directly (coordinate
// variables, other dimension orders, HDF5), arrays that are not cubes, broken files, and MEM
// datasets handed over without a file. Coordinates that are uneven or skip lines:
// gdal_coordinates_test.cpp.

#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <chrono>
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

// A 3 x 300 x 260 cube of the formula, stored by `driver` with array creation `options`
// (BLOCKSIZE, COMPRESS).
void write_chunked(const std::string& path, const char* driver_name, std::vector<const char*> options) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driver_name);
  ASSERT_NE(driver, nullptr) << driver_name;
  GDALDataset* dataset = driver->CreateMultiDimensional(path.c_str(), nullptr, nullptr);
  ASSERT_NE(dataset, nullptr) << path;
  {
    auto root = dataset->GetRootGroup();
    auto il = root->CreateDimension("iline", "", "", 3);
    auto xl = root->CreateDimension("xline", "", "", 300);
    auto tw = root->CreateDimension("twt", "", "", 260);
    options.push_back(nullptr);
    auto array = root->CreateMDArray("seismic", {il, xl, tw}, GDALExtendedDataType::Create(GDT_Float32),
                                     const_cast<char**>(options.data()));
    ASSERT_NE(array, nullptr) << path;
    fill_array(*array, {0, 1, 2});
  }
  GDALClose(GDALDataset::ToHandle(dataset));
}

// Whole inline slices as chunks (netCDF's default for an unlimited first dimension): every block
// of the extraction that a slice spans reads, and decodes, all of it. The layout is a format
// detail, and when blocks of 128 read each chunk 8 times or more (here 1 x 3 x 3 = 9) opening the
// file warns and says how to rewrite it; chunks of a few blocks do not.
TEST(GdalMdForeign, ChunksThatBlocksReadManyTimesOverAreAWarning) {
  ScratchDir dir;
  struct Case {
    const char* driver;
    const char* file;
    std::vector<const char*> options;
    std::string chunks; // the "chunks" detail starts so (GDAL's Zarr names the dimensions dim0, ...)
    bool slow;
  };
  const std::vector<Case> cases{
      {"netCDF",
       "slices.nc",
       {"BLOCKSIZE=1,300,260", "COMPRESS=DEFLATE"},
       "1 x 300 x 260 samples (iline x xline x twt), deflate",
       true},
      {"Zarr", "slices.zarr", {"BLOCKSIZE=2,300,260"}, "2 x 300 x 260 samples (", true},
      {"netCDF", "tiles.nc", {"BLOCKSIZE=3,128,256"}, "3 x 128 x 256 samples (iline x xline x twt)", false},
  };
  for (const Case& c : cases) {
    const std::string path = dir.file(c.file);
    ASSERT_NO_FATAL_FAILURE(write_chunked(path, c.driver, c.options));
    const auto cube = gv::open_volume(path);
    std::string chunks, slow;
    for (const auto& d : cube->format_details()) {
      if (d.key == "chunks") chunks = d.value;
      if (d.key == "slow_reads") slow = d.value;
    }
    EXPECT_EQ(chunks.substr(0, c.chunks.size()), c.chunks) << c.file;
    const std::vector<std::string> warnings = gv::open_warnings(*cube);
    if (c.slow) {
      EXPECT_NE(slow.find("read each chunk about 9 times; run-workflow and extract copy it once (1 MiB"),
                std::string::npos)
          << slow;
      ASSERT_EQ(warnings.size(), 1u) << c.file;
      EXPECT_EQ(warnings[0], path + ": " + slow);
      // The command that rewrites it, for netCDF only (nccopy reads netCDF).
      EXPECT_EQ(slow.find("nccopy -c iline/64,xline/64,twt/64 ") != std::string::npos,
                std::string(c.driver) == "netCDF")
          << slow;
    } else {
      EXPECT_EQ(slow, "") << c.file;
      EXPECT_TRUE(warnings.empty()) << c.file;
    }
    // The layout changes how fast, never what is read.
    expect_formula(cube->read({{1, 100, 7}, {3, 290, 259}}), {{1, 100, 7}, {3, 290, 259}});
  }
}

// Such a file is copied once as raw float32 (one pass, each chunk decoded once), the copy is what
// reads go to from then on, and another process that opens the file with the first one's hint
// reads the copy too, but only while the file is the one the copy was made from. A well-chunked
// file needs no copy; a cancelled copy leaves nothing behind.
TEST(GdalMdForeign, AFileInSlicesIsReadFromOneCopyMadeOnce) {
  ScratchDir dir;
  const std::string path = dir.file("slices.nc"), copies = dir.file("copies");
  ASSERT_NO_FATAL_FAILURE(write_chunked(path, "netCDF", {"BLOCKSIZE=1,300,260", "COMPRESS=DEFLATE"}));
  const gv::Box box{{0, 0, 0}, {2, 9, 7}};

  {
    geotandem::CancelToken cancel;
    cancel.cancel();
    EXPECT_THROW(gv::open_volume(path)->use_block_copy(copies, nullptr, cancel), geotandem::Cancelled);
    EXPECT_TRUE(!fs::exists(copies) || fs::is_empty(copies)) << "a cancelled copy leaves no file";
  }
  const auto cube = gv::open_volume(path);
  EXPECT_EQ(cube->reopen_hint(), "");
  const std::string copy = cube->use_block_copy(copies, nullptr, {});
  ASSERT_FALSE(copy.empty());
  EXPECT_EQ(fs::path(copy).parent_path(), fs::path(copies));
  EXPECT_EQ(fs::file_size(copy), 3u * 300u * 260u * sizeof(float));
  EXPECT_EQ(cube->reopen_hint(), "block copy: " + copy);
  expect_formula(cube->read(cube->geometry().bounds()), cube->geometry().bounds());

  // What is read is the copy: a sample changed in it reads changed, here and in another process's
  // volume opened with the hint.
  {
    std::fstream raw(copy, std::ios::in | std::ios::out | std::ios::binary);
    const float marked = 12345.0f;
    raw.write(reinterpret_cast<const char*>(&marked), sizeof marked);
  }
  EXPECT_EQ(cube->read(box)[0], 12345.0f);
  gv::OpenOptions hinted;
  hinted.reopen_hint = cube->reopen_hint();
  EXPECT_EQ(gv::open_volume(path, hinted)->read(box)[0], 12345.0f);
  // A second volume asked for a copy takes the one there instead of writing it again.
  const auto written = fs::last_write_time(copy);
  EXPECT_EQ(gv::open_volume(path)->use_block_copy(copies, nullptr, {}), copy);
  EXPECT_EQ(fs::last_write_time(copy), written);

  // The file changed since: the hint no longer holds, and the file is read.
  fs::last_write_time(path, fs::last_write_time(path) + std::chrono::seconds(5));
  const auto changed = gv::open_volume(path, hinted);
  EXPECT_EQ(changed->reopen_hint(), "");
  expect_formula(changed->read(box), box);
  EXPECT_NE(changed->use_block_copy(copies, nullptr, {}), copy) << "a copy for the file as it is now";

  // Chunks of a few blocks: no copy, nothing written.
  const std::string tiles = dir.file("tiles.nc"), none = dir.file("none");
  ASSERT_NO_FATAL_FAILURE(write_chunked(tiles, "netCDF", {"BLOCKSIZE=3,128,256"}));
  EXPECT_EQ(gv::open_volume(tiles)->use_block_copy(none, nullptr, {}), "");
  EXPECT_FALSE(fs::exists(none));
}

// A CF-style file stored [time, y, x] with time unlimited is chunked in time slices: the copy then
// reads slabs along the samples, and reads what the file holds.
TEST(GdalMdForeign, AFileInTimeSlicesIsCopiedAlongTheSamples) {
  ScratchDir dir;
  const std::string path = dir.file("time-slices.nc");
  write_foreign(path, "netCDF", [](GDALGroup& root) {
    auto tw = root.CreateDimension("twt", "", "", 130);
    auto xl = root.CreateDimension("xline", "", "", 300);
    auto il = root.CreateDimension("iline", "", "", 260);
    const char* options[] = {"BLOCKSIZE=1,300,260", "COMPRESS=DEFLATE", nullptr};
    auto array = root.CreateMDArray("seismic", {tw, xl, il}, GDALExtendedDataType::Create(GDT_Float32),
                                    const_cast<char**>(options));
    ASSERT_NE(array, nullptr);
    // Written as Float32 (fill_array's Float64 goes sample by sample through netCDF: slow at this size).
    std::vector<float> values(130 * 300 * 260);
    std::size_t n = 0;
    for (std::int64_t k = 0; k < 130; ++k)
      for (std::int64_t j = 0; j < 300; ++j)
        for (std::int64_t i = 0; i < 260; ++i)
          values[n++] = value_at(i, j, k);
    const GUInt64 start[3] = {0, 0, 0};
    const std::size_t count[3] = {130, 300, 260};
    ASSERT_TRUE(array->Write(start, count, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float32), values.data()));
  });
  const auto cube = gv::open_volume(path);
  ASSERT_EQ(cube->geometry().shape, (gv::Index3{260, 300, 130}));
  const std::vector<std::string> warnings = gv::open_warnings(*cube);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("chunks of 1 x 300 x 260 samples (twt x xline x iline), deflate"), std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[0].find("copy it once (39 MiB"), std::string::npos) << warnings[0];
  const std::string copy = cube->use_block_copy(dir.file("copies"), nullptr, {});
  ASSERT_FALSE(copy.empty());
  EXPECT_EQ(fs::file_size(copy), 260u * 300u * 130u * sizeof(float));
  expect_formula(cube->read(cube->geometry().bounds()), cube->geometry().bounds());
  expect_formula(cube->read({{7, 100, 60}, {150, 290, 129}}), {{7, 100, 60}, {150, 290, 129}});
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
