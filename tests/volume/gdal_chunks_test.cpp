// Chunk layouts other tools leave, and the copy for reads by blocks (docs/formats-gdal.md,
// "Chunks"): whole inline slices and time slices are a warning and are copied once as raw float32,
// which reads, and other processes given the hint, then go to; well-chunked files are left alone.

#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "gdal_fixtures.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/volume/io.hpp"
#include "scratch.hpp"

namespace {

namespace fs = std::filesystem;
namespace gv = geotandem::volume;
using geotandem::testing::ScratchDir;
using namespace gdal_fixtures;

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

} // namespace
