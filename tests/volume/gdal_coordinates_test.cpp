// Coordinate variables that do not describe a regular grid, as files from other tools have them:
// unevenly spaced or decreasing ones refused, naming the values; line numbers that skip whole lines
// read as a survey with missing lines under the fill policy.

#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "gdal_fixtures.hpp"
#include "geotandem/volume/io.hpp"
#include "scratch.hpp"

namespace {

namespace gv = geotandem::volume;
using geotandem::testing::ScratchDir;
using namespace gdal_fixtures;

// A cube is a regular grid going down the trace: coordinates that are not evenly spaced (a gap in
// the line numbers, irregular sampling) or a sample axis that decreases are refused, naming the
// dimension and the values, instead of placing every sample after the first step wrongly. Float32
// seconds at 4 ms steps, whose rounding reaches a few parts in ten thousand of a step, still read.
TEST(GdalMdForeign, UnevenOrDecreasingCoordinatesAreRefused) {
  ScratchDir dir;
  auto write = [&](const std::string& name, std::vector<double> inlines, std::vector<double> times, GDALDataType type) {
    const std::string path = dir.file(name);
    write_axes(path, {Axis{"iline", 0, std::move(inlines), type}, Axis{"xline", 3},
                      Axis{"twt", 0, std::move(times), type, "s"}});
    return path;
  };
  std::vector<double> times;
  for (int k = 0; k < 2000; ++k)
    times.push_back(0.004 * k);
  const std::vector<double> inlines{500, 502, 504, 506};

  const auto fine = gv::open_volume(write("float32.nc", inlines, times, GDT_Float32));
  EXPECT_NEAR(fine->geometry().dz, 4.0, 1e-4);
  EXPECT_EQ(fine->geometry().inline_step, 2);

  const std::string gap = message_of([&] {
    gv::open_volume(write("gap.nc", {500, 502, 505, 507}, times, GDT_Float64));
  });
  EXPECT_NE(gap.find("dimension 'iline' is not evenly spaced: 502 then 505 after a step of 2"), std::string::npos)
      << gap;
  EXPECT_NE(gap.find("gap.nc"), std::string::npos) << gap;

  std::vector<double> uneven = times;
  uneven[1000] += 0.001;
  const std::string sampling = message_of([&] { gv::open_volume(write("uneven.nc", inlines, uneven, GDT_Float64)); });
  EXPECT_NE(sampling.find("dimension 'twt' is not evenly spaced"), std::string::npos) << sampling;

  std::vector<double> up(times.rbegin(), times.rend());
  const std::string reversed = message_of([&] { gv::open_volume(write("reversed.nc", inlines, up, GDT_Float64)); });
  EXPECT_NE(reversed.find("the sample axis 'twt' decreases: 7996 then 7992"), std::string::npos) << reversed;

  // Decreasing line numbers are a negative step, as in SEG-Y.
  const auto down = gv::open_volume(write("down.nc", {506, 504, 502, 500}, times, GDT_Float64));
  EXPECT_EQ(down->geometry().inline0, 506);
  EXPECT_EQ(down->geometry().inline_step, -2);
}

// Line numbers that skip whole lines (a survey with missing lines, as exported without padding):
// refused under the default NaN policy, naming the missing lines; under the fill policy the cube
// spans the whole grid, the stored lines in their places and the missing ones missing samples.
TEST(GdalMdForeign, MissingLinesAreMissingSamplesUnderTheFillPolicy) {
  ScratchDir dir;
  auto write = [&](const std::string& name, const std::vector<double>& inlines, const std::vector<double>& crosslines) {
    const std::string path = dir.file(name);
    write_axes(path, {Axis{"iline", 0, inlines}, Axis{"xline", 0, crosslines, GDT_Float32}, Axis{"twt", 7}});
    return path;
  };
  // Inline 506 is missing; crosslines 12 and 13; both in decreasing crossline order too.
  const std::string path = write("gaps.nc", {500, 502, 504, 508, 510}, {10, 11, 14, 15});
  const std::string refused = message_of([&] { gv::open_volume(path); });
  EXPECT_NE(refused.find("dimension 'iline' skip lines, missing: 506 (1 of 6 lines)"), std::string::npos) << refused;
  EXPECT_NE(refused.find("--nan fill"), std::string::npos) << refused;

  gv::OpenOptions fill;
  fill.nan_policy = gv::NanPolicy::fill;
  fill.fill_value = -7.0f;
  for (const bool down : {false, true}) {
    const std::vector<double> crosslines =
        down ? std::vector<double>{15, 14, 11, 10} : std::vector<double>{10, 11, 14, 15};
    const auto cube = gv::open_volume(write(down ? "down.nc" : "up.nc", {500, 502, 504, 508, 510}, crosslines), fill);
    const gv::Geometry& g = cube->geometry();
    EXPECT_EQ(g.shape, (gv::Index3{6, 6, 7}));
    EXPECT_EQ(g.inline0, 500);
    EXPECT_EQ(g.inline_step, 2);
    EXPECT_EQ(g.crossline0, down ? 15 : 10);
    EXPECT_EQ(g.crossline_step, down ? -1 : 1);
    std::string details;
    for (const auto& d : cube->format_details())
      if (d.key == "missing_lines") details = d.value;
    EXPECT_EQ(details, std::string("inlines 506 (1 of 6 lines); crosslines ") + (down ? "13 and 12" : "12 and 13") +
                           " (2 of 6 lines), read as missing samples");
    const auto warnings = gv::open_warnings(*cube);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0], cube->source() + ": missing lines: " + details);
    // Cube index -> stored index, -1 where missing.
    const std::vector<int> stored_inline{0, 1, 2, -1, 3, 4};
    const std::vector<int> stored_crossline{0, 1, -1, -1, 2, 3}; // in file order, rising or falling
    const auto whole = cube->read(g.bounds());
    for (std::int64_t i = 0; i < 6; ++i)
      for (std::int64_t j = 0; j < 6; ++j)
        for (std::int64_t k = 0; k < 7; ++k) {
          const int si = stored_inline[static_cast<std::size_t>(i)], sj = stored_crossline[static_cast<std::size_t>(j)];
          const float want = si < 0 || sj < 0 ? -7.0f : value_at(si, sj, k);
          ASSERT_EQ(whole[g.bounds().offset({i, j, k})], want) << i << " " << j << " " << k;
        }
    // Every box reads what the whole cube holds, whichever gaps it starts, ends or straddles in.
    std::mt19937 random(7);
    for (int n = 0; n < 60; ++n) {
      gv::Box box;
      for (int a = 0; a < 3; ++a) {
        std::uniform_int_distribution<std::int64_t> lo(0, g.shape[a] - 1);
        box.lo[a] = lo(random);
        std::uniform_int_distribution<std::int64_t> hi(box.lo[a] + 1, g.shape[a]);
        box.hi[a] = hi(random);
      }
      std::vector<float> cut(box.count());
      gv::copy_region(whole.data(), g.bounds(), cut.data(), box, box);
      ASSERT_EQ(cube->read(box), cut) << box.to_string();
    }
  }
  // A few lines spread over a range many times their number are not a survey with missing lines.
  const std::string sparse = message_of([&] {
    gv::open_volume(write("sparse.nc", {500, 502, 540, 560}, {10, 11, 12, 13}), fill);
  });
  EXPECT_NE(sparse.find("more than three lines in four"), std::string::npos) << sparse;
}

} // namespace
