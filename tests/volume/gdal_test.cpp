// GDAL-backed formats: netCDF-4, Zarr and GeoTIFF round trips through write_volume/open_volume,
// box reads across chunk boundaries, HDF5 and ENVI reading, files written by other tools, and the
// errors for arrays that are not cubes or files that are broken.

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

#include "geotandem/core/error.hpp"
#include "geotandem/volume/io.hpp"
#include "scratch.hpp"

namespace {

namespace fs = std::filesystem;
namespace gv = geotandem::volume;
using geotandem::testing::ScratchDir;

// Unique and exact in float32 for shapes below 100 on each axis, so a misplaced sample shows.
float value_at(std::int64_t i, std::int64_t j, std::int64_t k) {
  return static_cast<float>(i * 10000 + j * 100 + k) + 0.5f;
}

gv::Geometry test_geometry(gv::Index3 shape, gv::SampleUnit unit = gv::SampleUnit::milliseconds) {
  gv::Geometry g;
  g.shape = shape;
  g.inline0 = 1201;
  g.inline_step = 2;
  g.crossline0 = 3400.5;
  g.crossline_step = -1;
  g.z0 = 123.4;
  g.dz = 2.1;
  g.z_unit = unit;
  g.affine = {605123.25,  12.5 * std::cos(0.3), -25.0 * std::sin(0.3),
              6781234.75, 12.5 * std::sin(0.3), 25.0 * std::cos(0.3)};
  return g;
}

std::unique_ptr<gv::MemoryVolume> make_cube(const gv::Geometry& g) {
  std::vector<float> samples(g.sample_count());
  std::size_t n = 0;
  for (std::int64_t i = 0; i < g.shape[0]; ++i)
    for (std::int64_t j = 0; j < g.shape[1]; ++j)
      for (std::int64_t k = 0; k < g.shape[2]; ++k)
        samples[n++] = value_at(i, j, k);
  return std::make_unique<gv::MemoryVolume>(g, std::move(samples));
}

// Compares a box's samples with the formula; reports the first wrong index only.
void expect_formula(const std::vector<float>& samples, const gv::Box& box) {
  ASSERT_EQ(samples.size(), box.count());
  for (std::int64_t i = box.lo[0]; i < box.hi[0]; ++i)
    for (std::int64_t j = box.lo[1]; j < box.hi[1]; ++j)
      for (std::int64_t k = box.lo[2]; k < box.hi[2]; ++k)
        if (samples[box.offset({i, j, k})] != value_at(i, j, k)) {
          ADD_FAILURE() << "sample (" << i << ", " << j << ", " << k << ") of box " << box.to_string() << " is "
                        << samples[box.offset({i, j, k})] << ", expected " << value_at(i, j, k);
          return;
        }
}

std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const geotandem::FormatError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no FormatError thrown";
  return {};
}

class RecordingProgress final : public geotandem::Progress {
public:
  void begin(const std::string&, std::uint64_t total, const std::string&) override { total_ = total; }
  void update(std::uint64_t done) override { last_ = done; }
  void end() override { ended_ = true; }
  std::uint64_t total_ = 0, last_ = 0;
  bool ended_ = false;
};

// Writes a multidimensional file with GDAL directly, as another tool would; `fill` creates the
// content and must let go of every handle it makes.
void write_foreign(const std::string& path, const char* driver_name, const std::function<void(GDALGroup&)>& fill) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driver_name);
  ASSERT_NE(driver, nullptr);
  const char* options[] = {"FORMAT=NC4", nullptr};
  GDALDataset* dataset = driver->CreateMultiDimensional(path.c_str(), nullptr, options);
  ASSERT_NE(dataset, nullptr);
  {
    auto root = dataset->GetRootGroup();
    fill(*root);
  }
  GDALClose(GDALDataset::ToHandle(dataset));
}

std::shared_ptr<GDALMDArray> add_array(GDALGroup& root, const std::string& name,
                                       const std::vector<std::shared_ptr<GDALDimension>>& dims, GDALDataType type) {
  auto array = root.CreateMDArray(name, dims, GDALExtendedDataType::Create(type));
  EXPECT_NE(array, nullptr);
  return array;
}

// Fills a 3-D array whose stored axes hold (inline, crossline, sample) as given by `axes`:
// stored dimension d is cube axis axes[d].
void fill_array(GDALMDArray& array, std::array<int, 3> axes) {
  const auto& dims = array.GetDimensions();
  std::array<std::size_t, 3> count{};
  for (std::size_t d = 0; d < 3; ++d)
    count[d] = static_cast<std::size_t>(dims[d]->GetSize());
  std::vector<double> values(count[0] * count[1] * count[2]);
  std::size_t n = 0;
  for (std::size_t a = 0; a < count[0]; ++a)
    for (std::size_t b = 0; b < count[1]; ++b)
      for (std::size_t c = 0; c < count[2]; ++c) {
        std::array<std::int64_t, 3> cube{};
        cube[static_cast<std::size_t>(axes[0])] = static_cast<std::int64_t>(a);
        cube[static_cast<std::size_t>(axes[1])] = static_cast<std::int64_t>(b);
        cube[static_cast<std::size_t>(axes[2])] = static_cast<std::int64_t>(c);
        values[n++] = value_at(cube[0], cube[1], cube[2]);
      }
  const GUInt64 start[3] = {0, 0, 0};
  ASSERT_TRUE(
      array.Write(start, count.data(), nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float64), values.data()));
}

void write_coordinate(GDALGroup& root, const std::shared_ptr<GDALDimension>& dim, double first, double step,
                      const char* unit) {
  auto variable = add_array(root, dim->GetName(), {dim}, GDT_Float64);
  std::vector<double> values(static_cast<std::size_t>(dim->GetSize()));
  for (std::size_t n = 0; n < values.size(); ++n)
    values[n] = first + step * static_cast<double>(n);
  const GUInt64 start = 0;
  const std::size_t count = values.size();
  ASSERT_TRUE(
      variable->Write(&start, &count, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float64), values.data()));
  if (unit) variable->CreateAttribute("units", {}, GDALExtendedDataType::CreateString())->Write(unit);
}

// ---- round trips, parameterised over the written formats -------------------------------------

struct Written {
  std::string extension;
  std::string format;
};

void PrintTo(const Written& written, std::ostream* out) {
  *out << written.extension;
}

class GdalRoundTrip : public ::testing::TestWithParam<Written> {};

TEST_P(GdalRoundTrip, DataGeometryAndFormatSurvive) {
  ScratchDir dir;
  for (auto unit : {gv::SampleUnit::milliseconds, gv::SampleUnit::metres}) {
    const auto source = make_cube(test_geometry({37, 29, 53}, unit));
    const std::string path = dir.file(std::string("cube_") + gv::to_string(unit) + GetParam().extension);
    gv::write_volume(*source, path, {.chunk = 16});
    EXPECT_EQ(gv::detect_format(path), GetParam().format);
    const auto cube = gv::open_volume(path);
    EXPECT_EQ(cube->format(), GetParam().format);
    EXPECT_EQ(cube->source(), path);
    EXPECT_EQ(cube->geometry(), source->geometry()) << "unit " << gv::to_string(unit);
    expect_formula(cube->read(cube->geometry().bounds()), cube->geometry().bounds());
  }
}

TEST_P(GdalRoundTrip, BoxesAcrossChunkBoundariesEqualTheWholeRead) {
  ScratchDir dir;
  const auto source = make_cube(test_geometry({37, 29, 53}));
  const std::string path = dir.file("cube" + GetParam().extension);
  gv::write_volume(*source, path, {.chunk = 16});
  const auto cube = gv::open_volume(path);
  const gv::Box all = cube->geometry().bounds();
  const std::vector<float> whole = cube->read(all);
  expect_formula(whole, all);

  std::vector<gv::Box> boxes{{{15, 15, 15}, {17, 17, 17}}, // the corner shared by 8 chunks
                             {{0, 0, 0}, {1, 1, 1}},       // one sample
                             {{30, 20, 40}, {37, 29, 53}}, // the clipped far chunks
                             {{10, 0, 31}, {11, 29, 49}},  // one inline, a full crossline range
                             {{3, 14, 0}, {36, 18, 53}}};  // whole traces across three inlines chunks
  std::mt19937 random(20240611);
  for (int n = 0; n < 25; ++n) {
    gv::Box box;
    for (int a = 0; a < 3; ++a) {
      std::uniform_int_distribution<std::int64_t> pick(0, all.hi[a] - 1);
      std::int64_t p = pick(random), q = pick(random);
      box.lo[a] = std::min(p, q);
      box.hi[a] = std::max(p, q) + 1;
    }
    boxes.push_back(box);
  }
  for (const gv::Box& box : boxes) {
    std::vector<float> part = cube->read(box);
    std::vector<float> expected(box.count());
    gv::copy_region(whole.data(), all, expected.data(), box, box);
    EXPECT_EQ(part, expected) << "box " << box.to_string();
  }
}

TEST_P(GdalRoundTrip, ProgressCountsChunksAndCancelLeavesNoFile) {
  ScratchDir dir;
  const auto source = make_cube(test_geometry({20, 17, 33}));
  RecordingProgress progress;
  gv::write_volume(*source, dir.file("done" + GetParam().extension), {.chunk = 16}, &progress);
  EXPECT_GT(progress.total_, 0u);
  EXPECT_EQ(progress.last_, progress.total_);
  EXPECT_TRUE(progress.ended_);

  geotandem::CancelToken cancel;
  cancel.cancel();
  const std::string path = dir.file("cancelled" + GetParam().extension);
  EXPECT_THROW(gv::write_volume(*source, path, {.chunk = 16}, nullptr, cancel), geotandem::Cancelled);
  EXPECT_FALSE(fs::exists(path));
}

TEST_P(GdalRoundTrip, ChunkLargerThanTheCube) {
  ScratchDir dir;
  const auto source = make_cube(test_geometry({3, 70, 5}));
  const std::string path = dir.file("small" + GetParam().extension);
  gv::write_volume(*source, path, {.chunk = 64});
  const auto cube = gv::open_volume(path);
  expect_formula(cube->read(cube->geometry().bounds()), cube->geometry().bounds());
  expect_formula(cube->read({{1, 60, 2}, {3, 70, 4}}), {{1, 60, 2}, {3, 70, 4}});
}

INSTANTIATE_TEST_SUITE_P(Formats, GdalRoundTrip,
                         ::testing::Values(Written{".nc", "netCDF-4"}, Written{".zarr", "Zarr"},
                                           Written{".tif", "GeoTIFF"}),
                         [](const auto& param) { return param.param.extension.substr(1); });

// ---- what the written files hold, seen through GDAL directly ---------------------------------

TEST(GdalMdLayout, WrittenFilesCarryDimensionsCoordinatesAttributesAndChunks) {
  ScratchDir dir;
  const gv::Geometry g = test_geometry({37, 29, 53});
  const auto source = make_cube(g);
  for (const char* extension : {".nc", ".zarr"}) {
    const std::string path = dir.file(std::string("cube") + extension);
    gv::write_volume(*source, path, {.chunk = 16, .variable = "amp"});
    GDALAllRegister();
    GDALDataset* dataset =
        GDALDataset::FromHandle(GDALOpenEx(path.c_str(), GDAL_OF_MULTIDIM_RASTER, nullptr, nullptr, nullptr));
    ASSERT_NE(dataset, nullptr) << path;
    {
      auto array = dataset->GetRootGroup()->OpenMDArray("amp");
      ASSERT_NE(array, nullptr) << path;
      const auto& dims = array->GetDimensions();
      ASSERT_EQ(dims.size(), 3u);
      EXPECT_EQ(dims[0]->GetName(), "iline");
      EXPECT_EQ(dims[1]->GetName(), "xline");
      EXPECT_EQ(dims[2]->GetName(), "twt");
      EXPECT_EQ(array->GetBlockSize(), (std::vector<GUInt64>{16, 16, 16})) << path;
      EXPECT_EQ(array->GetAttribute("geotandem_dz")->ReadAsDouble(), g.dz);
      EXPECT_EQ(array->GetAttribute("geotandem_xi")->ReadAsDouble(), g.affine.xi);
      EXPECT_STREQ(array->GetAttribute("geotandem_z_unit")->ReadAsString(), "ms");
      auto twt = dims[2]->GetIndexingVariable();
      ASSERT_NE(twt, nullptr) << path;
      std::vector<double> z(53);
      const GUInt64 start = 0;
      const std::size_t count = z.size();
      ASSERT_TRUE(twt->Read(&start, &count, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float64), z.data()));
      EXPECT_DOUBLE_EQ(z[10], g.z0 + 10 * g.dz);
      EXPECT_EQ(twt->GetUnit(), "ms");
    }
    GDALClose(GDALDataset::ToHandle(dataset));
  }
}

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

TEST(GdalRasterForeign, EnviWrittenThroughGdalOpensWithDefaults) {
  ScratchDir dir;
  const std::string path = dir.file("cube.bin");
  const gv::Index3 shape{6, 9, 11};
  GDALAllRegister();
  {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("ENVI");
    ASSERT_NE(driver, nullptr);
    GDALDataset* dataset = driver->Create(path.c_str(), static_cast<int>(shape[2]), static_cast<int>(shape[1]),
                                          static_cast<int>(shape[0]), GDT_Float32, nullptr);
    ASSERT_NE(dataset, nullptr);
    std::vector<float> slice(static_cast<std::size_t>(shape[1] * shape[2]));
    for (int b = 1; b <= shape[0]; ++b) {
      for (std::int64_t j = 0; j < shape[1]; ++j)
        for (std::int64_t k = 0; k < shape[2]; ++k)
          slice[static_cast<std::size_t>(j * shape[2] + k)] = value_at(b - 1, j, k);
      ASSERT_EQ(dataset->GetRasterBand(b)->RasterIO(
                    GF_Write, 0, 0, static_cast<int>(shape[2]), static_cast<int>(shape[1]), slice.data(),
                    static_cast<int>(shape[2]), static_cast<int>(shape[1]), GDT_Float32, 0, 0, nullptr),
                CE_None);
    }
    GDALClose(GDALDataset::ToHandle(dataset));
  }
  EXPECT_EQ(gv::detect_format(path), "ENVI");
  const auto cube = gv::open_volume(path);
  EXPECT_EQ(cube->format(), "ENVI");
  const gv::Geometry& g = cube->geometry();
  EXPECT_EQ(g.shape, shape);
  EXPECT_EQ(g.inline0, 0);
  EXPECT_EQ(g.crossline0, 0);
  EXPECT_EQ(g.dz, gv::Geometry{}.dz);
  expect_formula(cube->read(g.bounds()), g.bounds());
  expect_formula(cube->read({{2, 3, 4}, {5, 9, 10}}), {{2, 3, 4}, {5, 9, 10}});
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

// ---- threads ------------------------------------------------------------------------------------

TEST(GdalThreads, OneVolumePerThreadReadsCorrectlyAndQuietly) {
  ScratchDir dir;
  const auto source = make_cube(test_geometry({24, 20, 30}));
  const std::string path = dir.file("shared.nc");
  // HDF5's error printing is a per-thread setting and netCDF silences only the thread that
  // initialised it: write from a thread of its own so that (when this test runs alone, as under
  // ctest) the readers below are threads netCDF has never seen.
  std::thread([&] { gv::write_volume(*source, path, {.chunk = 8}); }).join();
  ::testing::internal::CaptureStderr();
  std::vector<std::thread> workers;
  std::vector<int> wrong(2, 0);
  for (int t = 0; t < 2; ++t)
    workers.emplace_back([&, t] {
      const auto cube = gv::open_volume(path);
      for (std::int64_t i = t; i < 24; i += 2) {
        const gv::Box box{{i, 0, 0}, {i + 1, 20, 30}};
        const std::vector<float> samples = cube->read(box);
        for (std::size_t n = 0; n < samples.size(); ++n)
          if (samples[n] != value_at(i, static_cast<std::int64_t>(n) / 30, static_cast<std::int64_t>(n) % 30))
            ++wrong[static_cast<std::size_t>(t)];
      }
    });
  for (auto& worker : workers)
    worker.join();
  const std::string noise = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(wrong, (std::vector<int>{0, 0}));
  EXPECT_TRUE(noise.empty()) << "GDAL or HDF5 wrote to stderr:\n" << noise.substr(0, 400);
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
