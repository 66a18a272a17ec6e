// The GDAL module (framework/volume/src/gdal_module.hpp): a process maps GDAL only once it opens or
// writes a GDAL-backed cube, the module then reads and writes as the library did, and a module
// that cannot be loaded is an IoError that names it and says what to do. This executable links no
// GDAL itself, so what /proc/self/maps shows is the library's doing. (Each test is its own process.)

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/io.hpp"
#include "io_fixtures.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;
using namespace geotandem;
using namespace geotandem::volume;
using geotandem::testing::ScratchDir;
using geotandem::volume::testing::formula_cube;
using geotandem::volume::testing::formula_samples;
using geotandem::volume::testing::sample_geometry;

namespace {

// Whether a mapped file of this process has `name` in its file name.
bool mapped(const std::string& name) {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line)) {
    const std::size_t slash = line.rfind('/');
    if (slash != std::string::npos && line.find(name, slash) != std::string::npos) return true;
  }
  return false;
}

} // namespace

TEST(GdalModule, GdalIsMappedOnlyOnceAGdalFormatIsUsed) {
  ScratchDir dir;
  const Geometry g = sample_geometry({6, 5, 24});
  const auto cube = formula_cube(g);
  ASSERT_TRUE(mapped("libgeotandem_volume.so")) << "the check reads the wrong maps";

  // Raw and SEG-Y go through no GDAL.
  write_volume(*cube, dir.file("cube.raw"));
  write_volume(*cube, dir.file("cube.sgy"));
  EXPECT_EQ(open_volume(dir.file("cube.raw"))->read(g.bounds()), formula_samples(g.bounds()));
  EXPECT_EQ(open_volume(dir.file("cube.sgy"))->read(g.bounds()), formula_samples(g.bounds()));
  EXPECT_FALSE(mapped("libgdal")) << "a raw or SEG-Y cube loaded GDAL";
  EXPECT_FALSE(mapped("libgeotandem_volume_gdal")) << "a raw or SEG-Y cube loaded the GDAL module";

  // netCDF-4 loads the module and GDAL with it, and round-trips every sample and the geometry.
  write_volume(*cube, dir.file("cube.nc"));
  EXPECT_TRUE(mapped("libgeotandem_volume_gdal"));
  EXPECT_TRUE(mapped("libgdal"));
  const auto back = open_volume(dir.file("cube.nc"));
  EXPECT_EQ(back->read(g.bounds()), formula_samples(g.bounds()));
  EXPECT_EQ(back->geometry().shape, g.shape);
  EXPECT_EQ(back->geometry().inline0, g.inline0);
  EXPECT_EQ(detect_format(dir.file("cube.nc")), "netCDF-4");
  // And GeoTIFF through the same, already loaded module.
  write_volume(*cube, dir.file("cube.tif"));
  EXPECT_EQ(open_volume(dir.file("cube.tif"))->read(g.bounds()), formula_samples(g.bounds()));
}

TEST(GdalModule, AModuleThatCannotBeLoadedIsAnIoErrorThatSaysWhatToDo) {
  ScratchDir dir;
  const std::string missing = dir.file("no-such-module.so");
  ASSERT_EQ(::setenv("GEOTANDEM_GDAL_MODULE", missing.c_str(), 1), 0); // before the first GDAL format
  const Geometry g = sample_geometry({4, 4, 8});
  const auto cube = formula_cube(g);
  for (int attempt = 0; attempt < 2; ++attempt) { // the second answer comes from the first load's record
    try {
      write_volume(*cube, dir.file("cube.nc"));
      FAIL() << "a netCDF-4 file was written without the GDAL module";
    } catch (const IoError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("netCDF-4 needs geotandem's GDAL module"), std::string::npos) << what;
      EXPECT_EQ(e.context().file, dir.file("cube.nc")) << what;
      EXPECT_NE(what.find(missing), std::string::npos) << what;
      EXPECT_NE(what.find("GEOTANDEM_GDAL_MODULE"), std::string::npos) << what;
      EXPECT_NE(what.find("SEG-Y and raw cubes do not need it"), std::string::npos) << what;
      EXPECT_EQ(e.exit_code(), 3);
    }
  }
  EXPECT_FALSE(fs::exists(dir.file("cube.nc")));
  EXPECT_FALSE(mapped("libgdal"));
  // Formats without GDAL still work in the same process.
  write_volume(*cube, dir.file("cube.raw"));
  EXPECT_EQ(open_volume(dir.file("cube.raw"))->read(g.bounds()), formula_samples(g.bounds()));
}
