// SEG-Y as delivered: every sample format segyio reads (1, 2, 3, 5, 8) in both byte orders, and
// line numbers at other header bytes than 189/193, written here through segyio and read back
// equal to segyio's own reading of the same file.

#include <gtest/gtest.h>
#include <segyio/segy.h>

#include <string>
#include <tuple>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/io.hpp"
#include "io_fixtures.hpp"
#include "scratch.hpp"
#include "segy_fixtures.hpp"

using namespace geotandem;
using namespace geotandem::volume;
using geotandem::testing::ScratchDir;
using geotandem::volume::testing::expected_sample;
using geotandem::volume::testing::message_of;
using geotandem::volume::testing::probe_boxes;
using geotandem::volume::testing::read_with_segyio;
using geotandem::volume::testing::SegySpec;
using geotandem::volume::testing::write_with_segyio;

namespace {

std::string detail(const Volume& v, const std::string& key) {
  for (const auto& d : v.format_details())
    if (d.key == key) return d.value;
  return "(no " + key + ")";
}

// What the file holds, from the spec: [i][j][k] in C order.
std::vector<float> written(const SegySpec& s) {
  std::vector<float> out;
  for (int i = 0; i < s.ni; ++i)
    for (int j = 0; j < s.nj; ++j)
      for (int k = 0; k < s.ns; ++k)
        out.push_back(expected_sample(s.format, i, j, k));
  return out;
}

// Reads `path` with geotandem and with segyio; both must agree with each other, sample for
// sample, and with what was written; every probe box must be the matching part of the whole.
void expect_same_as_segyio(const std::string& path, const SegySpec& s, const OpenOptions& options = {}) {
  int ni = 0, nj = 0;
  const std::vector<float> oracle = read_with_segyio(path, s.little_endian, s.inline_byte, s.crossline_byte, &ni, &nj);
  ASSERT_EQ(ni, s.ni);
  ASSERT_EQ(nj, s.nj);
  ASSERT_EQ(oracle, written(s)) << "the fixture or segyio disagrees with the spec";
  auto volume = open_volume(path, options);
  const Geometry& g = volume->geometry();
  ASSERT_EQ(g.shape, (Index3{s.ni, s.nj, s.ns}));
  const std::vector<float> whole = volume->read(g.bounds());
  ASSERT_EQ(whole.size(), oracle.size());
  std::size_t differences = 0;
  for (std::size_t n = 0; n < whole.size(); ++n)
    differences += whole[n] != oracle[n];
  EXPECT_EQ(differences, 0u) << "samples that differ from segyio's reading";
  for (const Box& box : probe_boxes(g.shape)) {
    std::vector<float> expected(box.count());
    copy_region(oracle.data(), g.bounds(), expected.data(), box, box);
    EXPECT_EQ(volume->read(box), expected) << box.to_string();
  }
}

// ---- Every sample format, both byte orders, both sortings ---------------------------------------

class SegyFormatTest : public ::testing::TestWithParam<std::tuple<int, bool, bool>> {};

TEST_P(SegyFormatTest, ReadsWhatSegyioReads) {
  ScratchDir dir;
  SegySpec s;
  s.format = std::get<0>(GetParam());
  s.little_endian = std::get<1>(GetParam());
  s.crossline_sorted = std::get<2>(GetParam());
  s.delay_ms = 8;
  const std::string path = dir.file("cube.sgy");
  write_with_segyio(path, s);
  // The byte order really is the one asked for: the format code's bytes.
  const std::string bytes = geotandem::volume::testing::read_bytes(path);
  EXPECT_EQ(bytes[s.little_endian ? 3224 : 3225], static_cast<char>(s.format));
  EXPECT_EQ(bytes[s.little_endian ? 3225 : 3224], 0);

  EXPECT_EQ(detect_format(path), "SEG-Y");
  expect_same_as_segyio(path, s);
  auto volume = open_volume(path);
  const Geometry& g = volume->geometry();
  EXPECT_EQ(g.inline0, s.il0);
  EXPECT_EQ(g.inline_step, s.il_step);
  EXPECT_EQ(g.crossline0, s.xl0);
  EXPECT_EQ(g.dz, 4.0);
  EXPECT_EQ(g.z0, 8.0);
  geotandem::volume::testing::expect_near_affine(g.affine, s.affine, 1e-6);
  EXPECT_NE(detail(*volume, "sample_format").find("(code " + std::to_string(s.format) + ")"), std::string::npos)
      << detail(*volume, "sample_format");
  EXPECT_EQ(detail(*volume, "byte_order"), s.little_endian ? "little-endian" : "big-endian");
  EXPECT_EQ(detail(*volume, "inline_byte"), "189");
  EXPECT_EQ(detail(*volume, "crossline_byte"), "193");
  EXPECT_EQ(detail(*volume, "sorting"), s.crossline_sorted ? "crossline-sorted" : "inline-sorted");
}

std::string format_case_name(const ::testing::TestParamInfo<std::tuple<int, bool, bool>>& info) {
  return "format" + std::to_string(std::get<0>(info.param)) + (std::get<1>(info.param) ? "_little" : "_big") +
         (std::get<2>(info.param) ? "_crossline" : "_inline");
}

INSTANTIATE_TEST_SUITE_P(FormatsByteOrdersSortings, SegyFormatTest,
                         ::testing::Combine(::testing::Values(SEGY_IBM_FLOAT_4_BYTE, SEGY_SIGNED_INTEGER_4_BYTE,
                                                              SEGY_SIGNED_SHORT_2_BYTE, SEGY_IEEE_FLOAT_4_BYTE,
                                                              SEGY_SIGNED_CHAR_1_BYTE),
                                            ::testing::Bool(), ::testing::Bool()),
                         format_case_name);

TEST(SegyFormats, LargeInt32SamplesRoundAsAPlainConversion) {
  // Past 2^24 a float cannot hold every integer; the reader must give what float(int) gives,
  // as segyio's users get from NumPy, not a value of its own.
  ScratchDir dir;
  SegySpec s;
  s.format = SEGY_SIGNED_INTEGER_4_BYTE;
  const std::string path = dir.file("int32.sgy");
  write_with_segyio(path, s);
  bool beyond = false;
  for (int k = 0; k < s.ns; ++k)
    beyond = beyond || std::abs(geotandem::volume::testing::integer_value(s.format, 6, 8, k)) > (1 << 24);
  ASSERT_TRUE(beyond) << "the fixture should reach past 2^24";
  expect_same_as_segyio(path, s);
}

TEST(SegyFormats, LittleEndianWithTheCountsInTraceHeadersOnly) {
  ScratchDir dir;
  SegySpec s;
  s.little_endian = true;
  s.format = SEGY_SIGNED_SHORT_2_BYTE;
  s.counts_in_trace_headers_only = true;
  s.interval_us = 2000;
  const std::string path = dir.file("le.sgy");
  write_with_segyio(path, s);
  auto volume = open_volume(path);
  EXPECT_EQ(volume->geometry().shape, (Index3{7, 9, 50}));
  EXPECT_EQ(volume->geometry().dz, 2.0);
  expect_same_as_segyio(path, s);
}

TEST(SegyFormats, UnreadableFormatCodeIsNamedInEitherByteOrder) {
  ScratchDir dir;
  for (bool little : {false, true}) {
    SegySpec s;
    s.format = SEGY_FIXED_POINT_WITH_GAIN_4_BYTE;
    s.little_endian = little;
    const std::string path = dir.file(little ? "le4.sgy" : "be4.sgy");
    write_with_segyio(path, s);
    const std::string message = message_of<FormatError>([&] { open_volume(path); });
    EXPECT_NE(message.find("format code 4 (fixed point with gain"), std::string::npos) << message;
    EXPECT_NE(message.find("16-bit integer (3)"), std::string::npos) << message;
    EXPECT_NE(message.find(path), std::string::npos) << message;
  }
}

// ---- Line numbers at other header bytes ---------------------------------------------------------

struct Positions {
  int inline_byte, crossline_byte;
};

class SegyHeaderBytesTest : public ::testing::TestWithParam<std::tuple<Positions, bool>> {};

TEST_P(SegyHeaderBytesTest, CommonPositionsAreSuggestedThenRead) {
  ScratchDir dir;
  SegySpec s;
  s.inline_byte = std::get<0>(GetParam()).inline_byte;
  s.crossline_byte = std::get<0>(GetParam()).crossline_byte;
  s.little_endian = std::get<1>(GetParam());
  s.format = SEGY_SIGNED_SHORT_2_BYTE;
  const std::string path = dir.file("moved.sgy");
  write_with_segyio(path, s);
  const std::string il = std::to_string(s.inline_byte), xl = std::to_string(s.crossline_byte);

  // Without options: refused, naming the positions that work and both ways to pass them.
  const std::string message = message_of<FormatError>([&] { open_volume(path); });
  EXPECT_NE(message.find("bytes " + il + "/" + xl + " do describe a regular inline-sorted grid of 7 inlines x 9"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("--inline-byte " + il + " --crossline-byte " + xl), std::string::npos) << message;
  EXPECT_NE(message.find("segy: {inline_byte: " + il + ", crossline_byte: " + xl + "}"), std::string::npos) << message;
  EXPECT_NE(message.find(path), std::string::npos) << message;

  // With them: the same cube segyio reads at those positions, and info names them.
  OpenOptions options;
  options.segy = {s.inline_byte, s.crossline_byte};
  expect_same_as_segyio(path, s, options);
  auto volume = open_volume(path, options);
  EXPECT_EQ(volume->geometry().inline0, s.il0);
  EXPECT_EQ(volume->geometry().inline_step, s.il_step);
  EXPECT_EQ(volume->geometry().crossline0, s.xl0);
  EXPECT_EQ(detail(*volume, "inline_byte"), il);
  EXPECT_EQ(detail(*volume, "crossline_byte"), xl);
}

INSTANTIATE_TEST_SUITE_P(CommonAlternatives, SegyHeaderBytesTest,
                         ::testing::Combine(::testing::Values(Positions{9, 21}, Positions{5, 21}, Positions{17, 13}),
                                            ::testing::Bool()));

TEST(SegyHeaderBytes, StandardPositionsAreSuggestedWhenOthersWereAskedFor) {
  ScratchDir dir;
  SegySpec s;
  const std::string path = dir.file("standard.sgy");
  write_with_segyio(path, s);
  OpenOptions options;
  options.segy = {9, 21};
  const std::string message = message_of<FormatError>([&] { open_volume(path, options); });
  EXPECT_NE(message.find("bytes 189/193 do describe"), std::string::npos) << message;
  EXPECT_NE(message.find("--inline-byte 189 --crossline-byte 193"), std::string::npos) << message;
}

TEST(SegyHeaderBytes, UncommonPositionsReadOnlyWhenGiven) {
  ScratchDir dir;
  SegySpec s;
  s.inline_byte = 197; // shot point
  s.crossline_byte = 225;
  s.crossline_sorted = true;
  const std::string path = dir.file("uncommon.sgy");
  write_with_segyio(path, s);
  const std::string message = message_of<FormatError>([&] { open_volume(path); });
  EXPECT_NE(message.find("9/21, 5/21 and 17/13 do not describe a regular grid either"), std::string::npos) << message;
  EXPECT_NE(message.find("--inline-byte"), std::string::npos) << message;
  OpenOptions options;
  options.segy = {197, 225};
  expect_same_as_segyio(path, s, options);
}

// Any byte whose field ends within the 240-byte header is a position (221 included, issue 54);
// others, and line number fields that overlap, are refused before the file is read.
TEST(SegyHeaderBytes, PositionsThatAreNoFieldAreRefused) {
  ScratchDir dir;
  const std::string path = dir.file("standard.sgy");
  write_with_segyio(path, SegySpec{});
  for (auto [il, xl, expected] :
       {std::tuple{238, 193, "the inline field at byte 238 (int32, 4 bytes) lies outside the 240-byte trace header"},
        std::tuple{189, 0, "the crossline field at byte 0"}, std::tuple{189, 241, "the crossline field at byte 241"},
        std::tuple{189, 189, "both 189"},
        std::tuple{189, 191, "bytes 189-192) and the crossline field (bytes 191-194"}}) {
    OpenOptions options;
    options.segy = {il, xl};
    const std::string message = message_of<InvalidArgument>([&] { open_volume(path, options); });
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_NE(message.find(path), std::string::npos) << message;
  }
}

TEST(SegyHeaderBytes, BrokenGridStillSaysWhatIsWrongWhenNoPositionHelps) {
  ScratchDir dir;
  SegySpec s;
  s.missing = {{3, 4}};
  s.little_endian = true;
  const std::string path = dir.file("missing.sgy");
  write_with_segyio(path, s);
  const std::string message = message_of<FormatError>([&] { open_volume(path); });
  EXPECT_NE(message.find("irregular survey at bytes 189/193: 62 of 63 traces"), std::string::npos) << message;
  EXPECT_NE(message.find("pad"), std::string::npos) << message;
  EXPECT_NE(message.find("--nan fill"), std::string::npos) << message;
  // Header bytes that give no grid at all still get the advice on other positions.
  OpenOptions elsewhere;
  elsewhere.segy = {73, 77}; // source coordinates: no line numbers
  const std::string other = message_of<FormatError>([&] { open_volume(path, elsewhere); });
  EXPECT_NE(other.find("do not describe a regular grid either"), std::string::npos) << other;
}

TEST(SegyHeaderBytes, ASingleLineIsNoAdviceForACube) {
  // Byte 9 constant and byte 21 counting traces make a regular 1 x N "grid"; a cube with a missing
  // trace at 189/193 must not be told to read it that way.
  ScratchDir dir;
  SegySpec s;
  s.missing = {{2, 2}};
  s.record_and_sequence = true;
  const std::string path = dir.file("sequence.sgy");
  write_with_segyio(path, s);
  const std::string message = message_of<FormatError>([&] { open_volume(path); });
  EXPECT_EQ(message.find("do describe"), std::string::npos) << message;
  EXPECT_NE(message.find("irregular survey"), std::string::npos) << message;
  // Asked for explicitly, the positions do read, as the single line they are.
  OpenOptions options;
  options.segy = {9, 21};
  EXPECT_EQ(open_volume(path, options)->geometry().shape, (Index3{1, 62, 50}));
}

} // namespace
