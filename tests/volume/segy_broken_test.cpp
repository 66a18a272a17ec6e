// SEG-Y files that are broken (truncated, pre-stack, misplaced, late or shuffled traces,
// unsupported sample formats): refused with messages that name the file. Irregular surveys and
// placeholders: segy_irregular_test.cpp.

#include <gtest/gtest.h>
#include <segyio/segy.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
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
using geotandem::volume::testing::expect_near_at_corners;
using geotandem::volume::testing::expect_same_grid;
using geotandem::volume::testing::formula;
using geotandem::volume::testing::formula_cube;
using geotandem::volume::testing::formula_samples;
using geotandem::volume::testing::message_of;
using geotandem::volume::testing::probe_boxes;
using geotandem::volume::testing::sample_geometry;
using geotandem::volume::testing::SegySpec;
using geotandem::volume::testing::write_with_segyio;

namespace {

// ---- Broken files -------------------------------------------------------------------------------

TEST(SegyBroken, TruncatedFileNamesTheFileAndBothSizes) {
  ScratchDir dir;
  const std::string path = dir.file("truncated.sgy");
  write_with_segyio(path, SegySpec{});
  const auto full = fs::file_size(path);
  fs::resize_file(path, full - 100);
  const std::string message = message_of<FormatError>([&] { open_volume(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find(std::to_string(full - 100)), std::string::npos) << message;
  EXPECT_NE(message.find(std::to_string(full)), std::string::npos) << message;

  // Cut at a trace boundary inside the second inline: whole traces, but not a whole grid.
  fs::resize_file(path, 3600 + 14 * (240 + 200));
  const std::string cut = message_of<FormatError>([&] { open_volume(path); });
  EXPECT_NE(cut.find("cut short"), std::string::npos) << cut;
  EXPECT_NE(cut.find(path), std::string::npos) << cut;
}

TEST(SegyBroken, PreStackFileIsRefusedWithTheOffsetCount) {
  ScratchDir dir;
  SegySpec s;
  s.offsets = 3;
  const std::string path = dir.file("gathers.sgy");
  write_with_segyio(path, s);
  const std::string message = message_of<FormatError>([&] { open_volume(path); });
  EXPECT_NE(message.find("pre-stack"), std::string::npos) << message;
  EXPECT_NE(message.find("3 traces"), std::string::npos) << message;
  EXPECT_NE(message.find(path), std::string::npos) << message;
}

TEST(SegyBroken, MisplacedTraceIsCaughtWhenRead) {
  ScratchDir dir;
  SegySpec s;
  s.swap_two_traces = true;
  const std::string path = dir.file("swapped.sgy");
  write_with_segyio(path, s);
  // The corners are in place, so opening works; the swapped traces must not be read as if they
  // were where the grid says.
  auto volume = open_volume(path);
  const std::string message = message_of<FormatError>([&] { volume->read(volume->geometry().bounds()); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("trace"), std::string::npos) << message;
  // Boxes away from the swapped pair still read.
  EXPECT_EQ(volume->read(Box{{0, 0, 0}, {1, 9, 50}}), formula_samples(Box{{0, 0, 0}, {1, 9, 50}}));
}

// A trace that starts later than the others (delay recording time): its samples would sit at the
// wrong times. Refused when read, naming the trace and both start times; other boxes still read,
// and so does the trace when it is flagged dead.
TEST(SegyBroken, ATraceStartingAtAnotherTimeIsCaughtWhenRead) {
  ScratchDir dir;
  SegySpec s;
  s.delay_ms = 100;
  s.late_trace = {3, 4};
  s.late_by_ms = 20;
  const std::string path = dir.file("late.sgy");
  write_with_segyio(path, s);
  auto volume = open_volume(path);
  EXPECT_EQ(volume->geometry().z0, 100);
  const std::string message = message_of<FormatError>([&] { volume->read(volume->geometry().bounds()); });
  EXPECT_NE(message.find("(inline 106, crossline 304) starts at 120 where the cube's first trace starts at 100"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_EQ(volume->read(Box{{0, 0, 0}, {1, 9, 50}}), formula_samples(Box{{0, 0, 0}, {1, 9, 50}}));

  // Flagged dead (trace identification code 2), the same trace reads: a padding trace's zeros have
  // no time to be wrong about.
  s.late_trace_dead = true;
  const std::string dead = dir.file("dead.sgy");
  write_with_segyio(dead, s);
  auto padded = open_volume(dead);
  EXPECT_EQ(padded->read(padded->geometry().bounds()), formula_samples(padded->geometry().bounds()));
}

// Traces in a random order are read through the trace index built from every header: every
// sample lands in its bin (issue 54; they were refused before).
TEST(SegyBroken, ShuffledTracesAreReadThroughATraceIndex) {
  ScratchDir dir;
  SegySpec s;
  s.shuffle = true;
  const std::string path = dir.file("shuffled.sgy");
  write_with_segyio(path, s);
  auto volume = open_volume(path);
  EXPECT_EQ(volume->geometry().shape, (Index3{7, 9, 50}));
  EXPECT_EQ(volume->read(volume->geometry().bounds()), formula_samples(volume->geometry().bounds()));
  EXPECT_EQ(volume->read(Box{{2, 3, 5}, {5, 8, 40}}), formula_samples(Box{{2, 3, 5}, {5, 8, 40}}));
}

TEST(SegyBroken, UnsupportedSampleFormatIsNamed) {
  ScratchDir dir;
  SegySpec s;
  s.format = SEGY_NOT_IN_USE_2; // 7: 24-bit integers
  const std::string path = dir.file("int24.sgy");
  write_with_segyio(path, s);
  const std::string message = message_of<FormatError>([&] { open_volume(path); });
  EXPECT_NE(message.find("format code 7 (24-bit integer"), std::string::npos) << message;
  EXPECT_NE(message.find(path), std::string::npos) << message;
}

} // namespace
