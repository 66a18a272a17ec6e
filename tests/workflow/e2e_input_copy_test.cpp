// A netCDF cube stored in whole inline slices (netCDF's default chunking for an unlimited first
// dimension): every block of the extraction would read, and decode, every slice it spans. The run
// copies the file once and every process reads the copy (docs/formats-gdal.md, "Chunks"): the
// same components as from the same samples in small chunks, no copy left behind, and workers that
// read the copy the manager names, not the file.

#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <vector>

#include "e2e_support.hpp"
#include "geotandem/volume/io.hpp"

namespace fs = std::filesystem;
using namespace geotandem;
using namespace geotandem::testing;

namespace {

// The samples of `cube` as a netCDF-4 array iline x xline x twt with array creation `options`.
void write_netcdf(const volume::Volume& cube, const std::string& path, std::vector<const char*> options) {
  const volume::Index3 n = cube.geometry().shape;
  const std::vector<float> samples = cube.read(cube.geometry().bounds());
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("netCDF");
  ASSERT_NE(driver, nullptr);
  GDALDataset* dataset = driver->CreateMultiDimensional(path.c_str(), nullptr, nullptr);
  ASSERT_NE(dataset, nullptr) << path;
  {
    auto root = dataset->GetRootGroup();
    auto il = root->CreateDimension("iline", "", "", static_cast<GUInt64>(n[0]));
    auto xl = root->CreateDimension("xline", "", "", static_cast<GUInt64>(n[1]));
    auto tw = root->CreateDimension("twt", "", "", static_cast<GUInt64>(n[2]));
    options.push_back(nullptr);
    auto array = root->CreateMDArray("amplitude", {il, xl, tw}, GDALExtendedDataType::Create(GDT_Float32),
                                     const_cast<char**>(options.data()));
    ASSERT_NE(array, nullptr) << path;
    const GUInt64 start[3] = {0, 0, 0};
    const std::size_t count[3] = {static_cast<std::size_t>(n[0]), static_cast<std::size_t>(n[1]),
                                  static_cast<std::size_t>(n[2])};
    ASSERT_TRUE(
        array->Write(start, count, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float32), samples.data()));
  }
  GDALClose(GDALDataset::ToHandle(dataset));
}

std::string recipe_for(const fs::path& dir, const std::string& cube) {
  const fs::path path = dir / (fs::path(cube).stem().string() + ".yaml");
  std::ofstream(path) << "version: 1\n"
                         "input:\n  file: "
                      << cube
                      << "\nsteps:\n  - step: extract\n    input: input\n    iso: 0.8\n    max_error: 0.5\n"
                         "output:\n  directory: out\n  store: store\n"
                         "execution:\n  scheduler: local\n  workers: 2\n";
  return path.string();
}

std::vector<std::uint64_t> keys_of(const fs::path& store_dir) {
  std::vector<std::uint64_t> keys;
  for (const auto& row : store::ComponentStore::open(store_dir).query())
    keys.push_back(row.key);
  std::sort(keys.begin(), keys.end());
  return keys;
}

} // namespace

TEST(WorkflowInputCopy, AFileInInlineSlicesIsReadFromOneCopyByEveryWorker) {
  ScratchDir dir;
  const std::string source = dir.file("source.nc"), tiles = dir.file("tiles.nc"), slices = dir.file("slices.nc");
  // 40 x 300 x 260: blocks of 128 read each 300 x 260 slice 3 x 3 = 9 times.
  auto made = run_geotandem("--quiet synth --kind seismic --shape 40 300 260 --seed 2 --out " + source);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  {
    const auto cube = volume::open_volume(source);
    ASSERT_NO_FATAL_FAILURE(write_netcdf(*cube, tiles, {"BLOCKSIZE=8,64,64"}));
    ASSERT_NO_FATAL_FAILURE(write_netcdf(*cube, slices, {"BLOCKSIZE=1,300,260", "COMPRESS=DEFLATE"}));
  }

  const fs::path out_tiles = dir.path() / "out-tiles", out_slices = dir.path() / "out-slices";
  auto reference = run_workflow(recipe_for(dir.path(), tiles), out_tiles);
  ASSERT_EQ(reference.command.exit_code, 0) << reference.command.err;
  EXPECT_EQ(reference.command.err.find("copy"), std::string::npos) << reference.command.err;
  auto copied = run_workflow(recipe_for(dir.path(), slices), out_slices);
  ASSERT_EQ(copied.command.exit_code, 0) << copied.command.err;
  const std::string& log = copied.command.err;
  EXPECT_NE(log.find("read each chunk about 9 times"), std::string::npos) << log;
  EXPECT_NE(log.find("reading " + slices + " from its copy " + (out_slices / "input-copy").string()), std::string::npos)
      << log;
  EXPECT_NE(log.find("removed the copy of the input"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(out_slices / "input-copy")) << "the copy goes when the run is done";
  const auto keys = keys_of(out_tiles / "store");
  ASSERT_GT(keys.size(), 5u);
  EXPECT_EQ(keys_of(out_slices / "store"), keys) << "the same components from the copy";

  // `geotandem extract` does the same beside its store, also given as "DIR/".
  const fs::path extracted = dir.path() / "extracted";
  auto cli = run_geotandem("extract " + slices + " --iso 0.8 --workers 2 --out " + extracted.string() + "/");
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  EXPECT_NE(cli.err.find("from its copy " + extracted.string() + ".input-copy/"), std::string::npos) << cli.err;
  EXPECT_FALSE(fs::exists(extracted.string() + ".input-copy"));
  EXPECT_EQ(keys_of(extracted), keys);

  // The workers read the copy the manager names: a copy already there (here made beforehand, then
  // zeroed) is taken as it is, and the extraction, all of it in the workers, finds nothing.
  const fs::path out_zero = dir.path() / "out-zero";
  const std::string copy = volume::open_volume(slices)->use_block_copy((out_zero / "input-copy").string(), nullptr, {});
  ASSERT_FALSE(copy.empty());
  {
    const std::vector<char> zeros(fs::file_size(copy), 0);
    std::ofstream(copy, std::ios::binary | std::ios::in | std::ios::out)
        .write(zeros.data(), static_cast<std::streamsize>(zeros.size()));
  }
  auto zero = run_workflow(recipe_for(dir.path(), slices), out_zero);
  ASSERT_EQ(zero.command.exit_code, 0) << zero.command.err;
  EXPECT_NE(zero.command.err.find("from its copy " + copy), std::string::npos) << zero.command.err;
  EXPECT_EQ(store::ComponentStore::open(out_zero / "store").size(), 0u) << zero.command.err;
}
