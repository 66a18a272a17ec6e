// SEG-Y files that are broken (truncated, uneven line numbers, pre-stack, missing, misplaced or
// shuffled traces, unsupported sample formats): refused with messages that name the file.

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

TEST(SegyBroken, UnevenLineNumbersAreNamed) {
  ScratchDir dir;
  SegySpec s;
  s.gap_in_inlines = true; // 100, 102, 104, 108, ...
  const std::string path = dir.file("gap.sgy");
  write_with_segyio(path, s);
  const std::string message = message_of<FormatError>([&] { open_volume(path); });
  EXPECT_NE(message.find("104 then 108"), std::string::npos) << message;
  EXPECT_NE(message.find(path), std::string::npos) << message;
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

TEST(SegyBroken, MissingTracesAreRefused) {
  ScratchDir dir;
  for (bool crossline_sorted : {false, true}) {
    SegySpec s;
    s.crossline_sorted = crossline_sorted;
    s.missing = {{3, 4}};
    const std::string path = dir.file(crossline_sorted ? "xl.sgy" : "il.sgy");
    write_with_segyio(path, s);
    const std::string message = message_of<FormatError>([&] { open_volume(path); });
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("pad"), std::string::npos) << message;
  }
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

TEST(SegyBroken, ShuffledTracesAreRefused) {
  ScratchDir dir;
  SegySpec s;
  s.shuffle = true;
  const std::string path = dir.file("shuffled.sgy");
  write_with_segyio(path, s);
  // Refused at open or, at the latest, when the traces are read: never read into the wrong place.
  const std::string message = message_of<FormatError>([&] {
    auto volume = open_volume(path);
    volume->read(volume->geometry().bounds());
  });
  EXPECT_NE(message.find(path), std::string::npos) << message;
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
