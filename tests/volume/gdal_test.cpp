// GDAL-backed formats: netCDF-4, Zarr and GeoTIFF round trips through write_volume/open_volume,
// box reads across chunk boundaries, the layout of written files, reads from several threads.
// Files from other tools, broken files and MEM datasets: gdal_foreign_test.cpp.

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
