// SEG-Y: files written here through segyio itself (not through our writer) with known line
// numbers, coordinates and samples, read back through open_volume; our writer's files read back
// by us and by segyio. Broken files: segy_broken_test.cpp.

#include <gtest/gtest.h>
#include <segyio/segy.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/io.hpp"
#include "io_fixtures.hpp"
#include "scratch.hpp"
#include "segy_fixtures.hpp"

namespace fs = std::filesystem;
using namespace geotandem;
using namespace geotandem::volume;
using geotandem::testing::ScratchDir;
using geotandem::volume::testing::formula;
using geotandem::volume::testing::formula_cube;
using geotandem::volume::testing::formula_samples;
using geotandem::volume::testing::message_of;
using geotandem::volume::testing::probe_boxes;
using geotandem::volume::testing::sample_geometry;
using geotandem::volume::testing::SegySpec;
using geotandem::volume::testing::write_with_segyio;

namespace {

// ---- Files written by segyio, read by us --------------------------------------------------------

// format x sorting x inline numbering (ascending, descending)
class SegyReadTest : public ::testing::TestWithParam<std::tuple<int, bool, int>> {};

TEST_P(SegyReadTest, GeometryAndSamplesComeBackFromSegyioFiles) {
  ScratchDir dir;
  SegySpec s;
  s.format = std::get<0>(GetParam());
  s.crossline_sorted = std::get<1>(GetParam());
  s.il_step = std::get<2>(GetParam());
  s.delay_ms = 24;
  const std::string path = dir.file("cube.sgy");
  write_with_segyio(path, s);

  EXPECT_EQ(detect_format(path), "SEG-Y");
  auto volume = open_volume(path);
  EXPECT_EQ(volume->format(), "SEG-Y");
  EXPECT_EQ(volume->source(), path);
  const Geometry& g = volume->geometry();
  EXPECT_EQ(g.shape, (Index3{s.ni, s.nj, s.ns}));
  EXPECT_EQ(g.inline0, s.il0);
  EXPECT_EQ(g.inline_step, s.il_step);
  EXPECT_EQ(g.crossline0, s.xl0);
  EXPECT_EQ(g.crossline_step, s.xl_step);
  EXPECT_EQ(g.dz, 4.0);
  EXPECT_EQ(g.z0, 24.0);
  EXPECT_EQ(g.z_unit, SampleUnit::milliseconds);
  geotandem::volume::testing::expect_near_affine(g.affine, s.affine, 1e-6);
  for (double i : {0.0, s.ni - 1.0})
    for (double j : {0.0, s.nj - 1.0}) {
      auto w = g.world(i, j, 10);
      auto expected = s.affine.apply(i, j);
      EXPECT_NEAR(w[0], expected[0], 1e-6) << i << "," << j;
      EXPECT_NEAR(w[1], expected[1], 1e-6) << i << "," << j;
      EXPECT_DOUBLE_EQ(w[2], 24.0 + 4.0 * 10);
    }

  const auto whole = volume->read(g.bounds());
  EXPECT_EQ(whole, formula_samples(g.bounds()));
  for (const Box& box : probe_boxes(g.shape)) {
    std::vector<float> expected(box.count());
    copy_region(whole.data(), g.bounds(), expected.data(), box, box);
    EXPECT_EQ(volume->read(box), expected) << box.to_string();
  }
}

INSTANTIATE_TEST_SUITE_P(FormatsAndSortings, SegyReadTest,
                         ::testing::Combine(::testing::Values(SEGY_IBM_FLOAT_4_BYTE, SEGY_IEEE_FLOAT_4_BYTE),
                                            ::testing::Bool(), ::testing::Values(2, -3)));

TEST(SegyRead, CoordinateScalarMultipliesWhenPositiveAndIsOneWhenZero) {
  ScratchDir dir;
  for (int scalar : {10, 0, 1, -10}) {
    SegySpec s;
    s.scalar = scalar;
    s.affine = SurveyAffine{500000, 20, -10, 6700000, 10, 30};
    const std::string path = dir.file("scalar" + std::to_string(scalar) + ".sgy");
    write_with_segyio(path, s);
    auto volume = open_volume(path);
    geotandem::volume::testing::expect_near_affine(volume->geometry().affine, s.affine, 1e-6);
  }
}

TEST(SegyRead, SingleInlineGetsAPerpendicularInlineDirection) {
  ScratchDir dir;
  SegySpec s;
  s.ni = 1;
  s.affine = SurveyAffine{1000, 0, 0, 2000, 0, 12.5}; // crosslines run north
  const std::string path = dir.file("line.sgy");
  write_with_segyio(path, s);
  auto volume = open_volume(path);
  const SurveyAffine& a = volume->geometry().affine;
  EXPECT_NEAR(a.xj, 0.0, 1e-9);
  EXPECT_NEAR(a.yj, 12.5, 1e-9);
  EXPECT_NEAR(a.xi * a.xj + a.yi * a.yj, 0.0, 1e-9); // perpendicular
  EXPECT_NEAR(a.step_i(), a.step_j(), 1e-9);
  EXPECT_EQ(volume->read(volume->geometry().bounds()), formula_samples(volume->geometry().bounds()));
}

TEST(SegyRead, ExtendedTextualHeadersAreSkipped) {
  ScratchDir dir;
  SegySpec s;
  s.extended_headers = 2;
  const std::string path = dir.file("extended.sgy");
  write_with_segyio(path, s);
  ASSERT_EQ(fs::file_size(path), 3600u + 2 * 3200u + 63u * (240u + 200u));
  auto volume = open_volume(path);
  EXPECT_EQ(volume->geometry().shape, (Index3{7, 9, 50}));
  EXPECT_EQ(volume->read(volume->geometry().bounds()), formula_samples(volume->geometry().bounds()));
}

TEST(SegyRead, SampleCountAndIntervalFallBackToTheTraceHeader) {
  ScratchDir dir;
  SegySpec s;
  s.counts_in_trace_headers_only = true;
  s.interval_us = 2500;
  const std::string path = dir.file("zeros.sgy");
  write_with_segyio(path, s);
  auto volume = open_volume(path);
  EXPECT_EQ(volume->geometry().shape, (Index3{7, 9, 50}));
  EXPECT_EQ(volume->geometry().dz, 2.5);
  EXPECT_EQ(volume->read(volume->geometry().bounds()), formula_samples(volume->geometry().bounds()));
}

TEST(SegyRead, FilesWithoutCoordinatesGetTheDefaultGrid) {
  ScratchDir dir;
  SegySpec s;
  s.coordinates = false;
  const std::string path = dir.file("nocoords.sgy");
  write_with_segyio(path, s);
  auto volume = open_volume(path);
  EXPECT_EQ(volume->geometry().affine, SurveyAffine{});
}

// Longitude and latitude (byte 89: 2 seconds of arc, 3 decimal degrees, 4 DDDMMSS) become metres
// east and north of the first trace, at 5 E, 60 N. Inlines step east in longitude, crosslines north
// in latitude: 2 and 1 seconds of arc (the same survey in DDDMMSS), or 0.001 and 0.0005 degrees
// (the 2-byte scalar of byte 71 allows no finer degrees than 1e-4). The figures they must give come
// from the published WGS84 lengths of a degree at 60 degrees of latitude: 55,799.98 m of longitude
// and 111,412.24 m of latitude. Lengths (units 1) stay as written, and a survey with missing traces
// (its affine fitted to every trace) agrees.
TEST(SegyRead, GeographicCoordinatesBecomeMetresEastAndNorthOfTheFirstTrace) {
  ScratchDir dir;
  constexpr double lon_degree = 55799.98, lat_degree = 111412.24;
  struct Case {
    int units, scalar;
    SurveyAffine affine; // in the file's units
    double east, north;  // metres per inline and per crossline
    const char* named;
  };
  const Case cases[] = {{2, -100, SurveyAffine{18000.0, 2.0, 0.0, 216000.0, 0.0, 1.0}, 2.0 / 3600.0 * lon_degree,
                         1.0 / 3600.0 * lat_degree, "seconds of arc"},
                        {3, -10000, SurveyAffine{5.0, 0.001, 0.0, 60.0, 0.0, 0.0005}, 0.001 * lon_degree,
                         0.0005 * lat_degree, "decimal degrees"},
                        {4, -100, SurveyAffine{50000.0, 2.0, 0.0, 600000.0, 0.0, 1.0}, 2.0 / 3600.0 * lon_degree,
                         1.0 / 3600.0 * lat_degree, "degrees, minutes and seconds"}};
  for (const Case& c : cases)
    for (bool irregular : {false, true}) {
      SCOPED_TRACE("units " + std::to_string(c.units) + (irregular ? ", traces missing" : ""));
      SegySpec s;
      s.coordinate_units = c.units;
      s.scalar = c.scalar;
      s.affine = c.affine;
      if (irregular) s.missing = {{6, 8}, {3, 4}};
      const std::string path = dir.file("geographic" + std::to_string(c.units) + (irregular ? "m" : "") + ".sgy");
      write_with_segyio(path, s);
      OpenOptions options;
      options.nan_policy = NanPolicy::fill;
      auto volume = open_volume(path, options);
      const SurveyAffine& a = volume->geometry().affine;
      EXPECT_NEAR(a.x0, 0.0, 0.01);
      EXPECT_NEAR(a.y0, 0.0, 0.01);
      EXPECT_NEAR(a.xi, c.east, 0.01);
      EXPECT_NEAR(a.yi, 0.0, 0.01);
      EXPECT_NEAR(a.xj, 0.0, 0.01);
      EXPECT_NEAR(a.yj, c.north, 0.01);
      std::string said;
      for (const auto& d : volume->format_details())
        if (d.key == "coordinates") said = d.value;
      EXPECT_NE(said.find(c.named), std::string::npos) << said;
      EXPECT_NE(said.find("longitude 5.000000, latitude 60.000000"), std::string::npos) << said;
    }
  SegySpec lengths;
  lengths.coordinate_units = 1;
  const std::string path = dir.file("lengths.sgy");
  write_with_segyio(path, lengths);
  auto volume = open_volume(path);
  geotandem::volume::testing::expect_near_affine(volume->geometry().affine, lengths.affine, 1e-6);
  for (const auto& d : volume->format_details())
    EXPECT_NE(d.key, "coordinates");
}

// ---- Our writer ---------------------------------------------------------------------------------

TEST(SegyWrite, RoundTripKeepsGeometryAndSamples) {
  ScratchDir dir;
  Geometry g = sample_geometry();
  g.z0 = 7.5; // needs the rev 1 time scalar
  auto cube = formula_cube(g);
  const std::string path = dir.file("out.segy");
  write_volume(*cube, path);

  auto back = open_volume(path);
  const Geometry& b = back->geometry();
  geotandem::volume::testing::expect_same_grid(b, g);
  EXPECT_EQ(b.z_unit, g.z_unit);
  // Coordinates are stored in centimetres: corners within half a centimetre.
  for (double i : {0.0, g.shape[0] - 1.0})
    for (double j : {0.0, g.shape[1] - 1.0}) {
      auto expected = g.affine.apply(i, j), got = b.affine.apply(i, j);
      EXPECT_NEAR(got[0], expected[0], 0.011);
      EXPECT_NEAR(got[1], expected[1], 0.011);
    }
  EXPECT_EQ(back->read(b.bounds()), cube->samples());
}

TEST(SegyWrite, DepthCubeComesBackInMetres) {
  ScratchDir dir;
  Geometry g = sample_geometry({3, 4, 20});
  g.z_unit = SampleUnit::metres;
  g.dz = 2.5;
  g.z0 = 1500;
  auto cube = formula_cube(g);
  const std::string path = dir.file("depth.sgy");
  write_volume(*cube, path);
  auto back = open_volume(path);
  EXPECT_EQ(back->geometry().z_unit, SampleUnit::metres);
  EXPECT_EQ(back->geometry().dz, 2.5);
  EXPECT_EQ(back->geometry().z0, 1500.0);
  EXPECT_EQ(back->read(g.bounds()), cube->samples());
}

TEST(SegyWrite, SegyioReadsOurFile) {
  ScratchDir dir;
  const Geometry g = sample_geometry();
  auto cube = formula_cube(g);
  const std::string path = dir.file("out.sgy");
  write_volume(*cube, path);

  segy_file* fp = segy_open(path.c_str(), "rb");
  ASSERT_NE(fp, nullptr);
  std::array<char, SEGY_BINARY_HEADER_SIZE> bin{};
  ASSERT_EQ(segy_binheader(fp, bin.data()), SEGY_OK);
  EXPECT_EQ(segy_format(bin.data()), SEGY_IEEE_FLOAT_4_BYTE);
  EXPECT_EQ(segy_samples(bin.data()), g.shape[2]);
  std::int32_t interval = 0, revision = 0;
  segy_get_bfield(bin.data(), SEGY_BIN_INTERVAL, &interval);
  segy_get_bfield(bin.data(), SEGY_BIN_SEGY_REVISION, &revision);
  EXPECT_EQ(interval, 2000);
  EXPECT_EQ(revision, 0x0100);
  const long trace0 = segy_trace0(bin.data());
  const int bytes = segy_trsize(SEGY_IEEE_FLOAT_4_BYTE, static_cast<int>(g.shape[2]));
  int traces = 0, sorting = 0, offsets = 0, il_count = 0, xl_count = 0;
  ASSERT_EQ(segy_traces(fp, &traces, trace0, bytes), SEGY_OK);
  EXPECT_EQ(traces, g.shape[0] * g.shape[1]);
  ASSERT_EQ(segy_sorting(fp, 189, 193, 37, &sorting, trace0, bytes), SEGY_OK);
  EXPECT_EQ(sorting, SEGY_INLINE_SORTING);
  ASSERT_EQ(segy_offsets(fp, 189, 193, traces, &offsets, trace0, bytes), SEGY_OK);
  EXPECT_EQ(offsets, 1);
  ASSERT_EQ(segy_lines_count(fp, 189, 193, sorting, offsets, &il_count, &xl_count, trace0, bytes), SEGY_OK);
  EXPECT_EQ(il_count, g.shape[0]);
  EXPECT_EQ(xl_count, g.shape[1]);
  std::vector<int> inlines(static_cast<std::size_t>(il_count)), crosslines(static_cast<std::size_t>(xl_count));
  ASSERT_EQ(segy_inline_indices(fp, 189, sorting, il_count, xl_count, 1, inlines.data(), trace0, bytes), SEGY_OK);
  ASSERT_EQ(segy_crossline_indices(fp, 193, sorting, il_count, xl_count, 1, crosslines.data(), trace0, bytes), SEGY_OK);
  for (int i = 0; i < il_count; ++i)
    EXPECT_EQ(inlines[static_cast<std::size_t>(i)], g.inline0 + i * g.inline_step);
  for (int j = 0; j < xl_count; ++j)
    EXPECT_EQ(crosslines[static_cast<std::size_t>(j)], g.crossline0 + j * g.crossline_step);

  // Trace (i, j) = (4, 6): coordinates with the scalar applied, and its samples.
  const int i = 4, j = 6, trace = i * xl_count + j;
  std::array<char, SEGY_TRACE_HEADER_SIZE> h{};
  ASSERT_EQ(segy_traceheader(fp, trace, h.data(), trace0, bytes), SEGY_OK);
  std::int32_t x = 0, y = 0, scalar = 0;
  segy_get_field(h.data(), SEGY_TR_CDP_X, &x);
  segy_get_field(h.data(), SEGY_TR_CDP_Y, &y);
  segy_get_field(h.data(), SEGY_TR_SOURCE_GROUP_SCALAR, &scalar);
  ASSERT_LT(scalar, 0);
  auto xy = g.affine.apply(i, j);
  EXPECT_NEAR(x / static_cast<double>(-scalar), xy[0], 0.006);
  EXPECT_NEAR(y / static_cast<double>(-scalar), xy[1], 0.006);
  std::vector<float> samples(static_cast<std::size_t>(g.shape[2]));
  ASSERT_EQ(segy_readtrace(fp, trace, samples.data(), trace0, bytes), SEGY_OK);
  segy_to_native(SEGY_IEEE_FLOAT_4_BYTE, static_cast<long long>(samples.size()), samples.data());
  for (int k = 0; k < g.shape[2]; ++k)
    EXPECT_EQ(samples[static_cast<std::size_t>(k)], formula(i, j, k)) << k;

  // The textual header is EBCDIC ('C' is 0xC3) and says who wrote it and the shape.
  std::array<char, SEGY_TEXT_HEADER_SIZE + 1> text{};
  ASSERT_EQ(segy_read_textheader(fp, text.data()), SEGY_OK);
  std::string header(text.data());
  EXPECT_NE(header.find("GEOTANDEM"), std::string::npos) << header;
  EXPECT_NE(header.find("7 INLINES X 9 CROSSLINES X 50 SAMPLES"), std::string::npos) << header;
  segy_close(fp);
  EXPECT_EQ(static_cast<unsigned char>(geotandem::volume::testing::read_bytes(path)[0]), 0xC3);
}

TEST(SegyWrite, RefusesWhatSegyCannotHoldAndLeavesNoFile) {
  ScratchDir dir;
  Geometry fractional = sample_geometry({2, 2, 4});
  fractional.inline0 = 10.5;
  Geometry odd_interval = sample_geometry({2, 2, 4});
  odd_interval.dz = 1.0 / 3.0;
  for (const Geometry& g : {fractional, odd_interval}) {
    const std::string path = dir.file("bad.sgy");
    auto cube = formula_cube(g);
    EXPECT_THROW(write_volume(*cube, path), InvalidArgument);
    EXPECT_FALSE(fs::exists(path));
  }
}

} // namespace
