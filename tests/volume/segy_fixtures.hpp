#pragma once
// SEG-Y files written through segyio's C API (not through our writer), with known line numbers,
// coordinates and samples, in any sample format segyio writes and either byte order, with line
// numbers at any header bytes, and the defects the tests need (missing, swapped or shuffled
// traces, gaps, extended headers); and segyio's own reading of such a file, the oracle the reader
// is compared with. Shared by the segy*_test.cpp files.

#include <gtest/gtest.h>
#include <segyio/segy.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "geotandem/volume/geometry.hpp"
#include "io_fixtures.hpp"

namespace geotandem::volume::testing {

// What the test writes through segyio's C API.
struct SegySpec {
  int ni = 7, nj = 9, ns = 50;
  int il0 = 100, il_step = 2, xl0 = 300, xl_step = 1;
  int format = SEGY_IEEE_FLOAT_4_BYTE;
  bool crossline_sorted = false;
  int interval_us = 4000;
  int delay_ms = 0;
  int scalar = -100;
  bool coordinates = true;
  SurveyAffine affine{500000.25, 10.0, -6.0, 6700000.5, 8.0, 7.5};
  int offsets = 1;
  std::vector<std::array<int, 2>> missing;   // (i, j) of traces left out
  bool swap_two_traces = false;              // trade the places of two inner traces
  bool shuffle = false;                      // traces in a random order
  bool gap_in_inlines = false;               // skip one inline number halfway
  int extended_headers = 0;                  // extended textual headers after the binary header
  bool counts_in_trace_headers_only = false; // binary header samples and interval left at 0
  bool little_endian = false;                // every header field and sample little-endian
  int inline_byte = SEGY_TR_INLINE;          // where the line numbers go (the other positions stay 0)
  int crossline_byte = SEGY_TR_CROSSLINE;
  bool record_and_sequence = false;      // field record 1 at byte 9, trace sequence at byte 21 (a 1 x N "grid")
  std::array<int, 2> late_trace{-1, -1}; // (i, j) of a trace whose delay is late_by_ms more than the others'
  int late_by_ms = 0;
  bool late_trace_dead = false; // that trace flagged dead (trace identification code 2)
  int coordinate_units = 0;     // written at byte 89 when not 0 (2: seconds of arc, 3: degrees, 4: DDDMMSS)
  // (i, j) of traces written in place as placeholders: flagged dead, every header field 0 but the
  // sample count and interval, samples 0.
  std::vector<std::array<int, 2>> placeholders;
  int trailing_placeholders = 0; // placeholders written after every trace of the survey

  long trace0() const { return 3600L + 3200L * extended_headers; }
  int inline_number(int i) const { return il0 + (i + (gap_in_inlines && i >= ni / 2 ? 1 : 0)) * il_step; }
};

// The sample formats segyio writes and geotandem reads.
inline bool readable_format(int format) {
  return format == SEGY_IBM_FLOAT_4_BYTE || format == SEGY_SIGNED_INTEGER_4_BYTE ||
         format == SEGY_SIGNED_SHORT_2_BYTE || format == SEGY_IEEE_FLOAT_4_BYTE || format == SEGY_SIGNED_CHAR_1_BYTE;
}

// The value written at (i, j, k) in a file of `format`: the formula for floats (exact in IBM
// too); integers that fill the type's range for the integer formats. 32-bit values reach past
// 2^24, where a float cannot hold every integer: the reader must round as a plain conversion does.
inline std::int64_t integer_value(int format, int i, int j, int k) {
  const std::int64_t id = (100 * i + j) * 64 + k; // unique while j < 100, k < 64
  switch (format) {
  case SEGY_SIGNED_INTEGER_4_BYTE: return id * 48611 - 1000000000; // |v| < 2^31 for id < 44000
  case SEGY_SIGNED_SHORT_2_BYTE: return (id * 37) % 65536 - 32768;
  default: return (id * 7) % 256 - 128; // 8-bit
  }
}

inline float expected_sample(int format, int i, int j, int k) {
  if (format == SEGY_IBM_FLOAT_4_BYTE || format == SEGY_IEEE_FLOAT_4_BYTE) return formula(i, j, k);
  return static_cast<float>(integer_value(format, i, j, k));
}

// One trace's samples in the file's encoding, big-endian (segyio swaps them when it writes a
// little-endian file).
inline std::vector<char> encoded_trace(int format, int i, int j, int ns) {
  std::vector<char> bytes;
  auto append = [&](auto value) {
    const auto* p = reinterpret_cast<const char*>(&value);
    bytes.insert(bytes.end(), p, p + sizeof(value));
  };
  for (int k = 0; k < ns; ++k) {
    switch (format) {
    case SEGY_SIGNED_INTEGER_4_BYTE: append(static_cast<std::int32_t>(integer_value(format, i, j, k))); break;
    case SEGY_SIGNED_SHORT_2_BYTE: append(static_cast<std::int16_t>(integer_value(format, i, j, k))); break;
    case SEGY_SIGNED_CHAR_1_BYTE: append(static_cast<std::int8_t>(integer_value(format, i, j, k))); break;
    default: append(formula(i, j, k)); break;
    }
  }
  segy_from_native(format, ns, bytes.data());
  return bytes;
}

inline double stored_factor(int scalar) {
  return scalar == 0 ? 1.0 : scalar > 0 ? 1.0 / scalar : -scalar;
}

inline void write_with_segyio(const std::string& path, const SegySpec& s) {
  segy_file* fp = segy_open(path.c_str(), "w+b");
  ASSERT_NE(fp, nullptr);
  // Formats geotandem does not read are laid out as 4-byte IEEE: only the code in the binary
  // header matters to the tests that write them.
  const int layout = readable_format(s.format) ? s.format : SEGY_IEEE_FLOAT_4_BYTE;
  // From here on segyio writes every header field and sample in the file's byte order.
  ASSERT_EQ(segy_set_format(fp, layout | (s.little_endian ? static_cast<int>(SEGY_LSB) : 0)), SEGY_OK);
  std::string text(3200, ' ');
  text.replace(0, 20, "C01 TEST CUBE SEGYIO");
  ASSERT_EQ(segy_write_textheader(fp, 0, text.c_str()), SEGY_OK);
  std::array<char, SEGY_BINARY_HEADER_SIZE> bin{};
  if (!s.counts_in_trace_headers_only) {
    segy_set_bfield(bin.data(), SEGY_BIN_INTERVAL, s.interval_us);
    segy_set_bfield(bin.data(), SEGY_BIN_SAMPLES, s.ns);
  }
  segy_set_bfield(bin.data(), SEGY_BIN_FORMAT, s.format);
  segy_set_bfield(bin.data(), SEGY_BIN_EXT_HEADERS, s.extended_headers);
  ASSERT_EQ(segy_write_binheader(fp, bin.data()), SEGY_OK);
  for (int n = 0; n < s.extended_headers; ++n)
    ASSERT_EQ(segy_write_textheader(fp, n + 1, text.c_str()), SEGY_OK);
  const int bytes = segy_trsize(layout, s.ns);

  // Positions in file order.
  std::vector<std::array<int, 2>> order;
  for (int outer = 0; outer < (s.crossline_sorted ? s.nj : s.ni); ++outer)
    for (int inner = 0; inner < (s.crossline_sorted ? s.ni : s.nj); ++inner) {
      std::array<int, 2> ij = s.crossline_sorted ? std::array<int, 2>{inner, outer} : std::array<int, 2>{outer, inner};
      bool skip = false;
      for (const auto& m : s.missing)
        skip = skip || m == ij;
      if (!skip) order.push_back(ij);
    }
  if (s.swap_two_traces) std::swap(order[order.size() / 2], order[order.size() / 2 + 1]);
  if (s.shuffle) std::shuffle(order.begin(), order.end(), std::mt19937(7));

  int trace = 0;
  const double factor = stored_factor(s.scalar);
  const auto write_placeholder = [&](int at) {
    std::array<char, SEGY_TRACE_HEADER_SIZE> h{};
    segy_set_field(h.data(), SEGY_TR_TRACE_ID, 2);
    segy_set_field(h.data(), SEGY_TR_SAMPLE_COUNT, s.ns);
    segy_set_field(h.data(), SEGY_TR_SAMPLE_INTER, s.interval_us);
    const std::vector<char> zeros(static_cast<std::size_t>(bytes), 0);
    return segy_write_traceheader(fp, at, h.data(), s.trace0(), bytes) == SEGY_OK &&
           segy_writetrace(fp, at, zeros.data(), s.trace0(), bytes) == SEGY_OK;
  };
  for (const auto& [i, j] : order)
    for (int offset = 1; offset <= s.offsets; ++offset, ++trace) {
      std::array<char, SEGY_TRACE_HEADER_SIZE> h{};
      if (std::find(s.placeholders.begin(), s.placeholders.end(), std::array<int, 2>{i, j}) != s.placeholders.end()) {
        ASSERT_TRUE(write_placeholder(trace));
        continue;
      }
      segy_set_field(h.data(), s.inline_byte, s.inline_number(i));
      segy_set_field(h.data(), s.crossline_byte, s.xl0 + j * s.xl_step);
      segy_set_field(h.data(), SEGY_TR_OFFSET, offset);
      if (s.record_and_sequence) {
        segy_set_field(h.data(), SEGY_TR_FIELD_RECORD, 1);
        segy_set_field(h.data(), SEGY_TR_ENSEMBLE, trace + 1);
      }
      segy_set_field(h.data(), SEGY_TR_SAMPLE_COUNT, s.ns);
      segy_set_field(h.data(), SEGY_TR_SAMPLE_INTER, s.interval_us);
      const bool late = std::array<int, 2>{i, j} == s.late_trace;
      segy_set_field(h.data(), SEGY_TR_DELAY_REC_TIME, s.delay_ms + (late ? s.late_by_ms : 0));
      if (late && s.late_trace_dead) segy_set_field(h.data(), SEGY_TR_TRACE_ID, 2);
      if (s.coordinates) {
        auto xy = s.affine.apply(i, j);
        segy_set_field(h.data(), SEGY_TR_SOURCE_GROUP_SCALAR, s.scalar);
        segy_set_field(h.data(), SEGY_TR_CDP_X, static_cast<int>(std::lround(xy[0] * factor)));
        segy_set_field(h.data(), SEGY_TR_CDP_Y, static_cast<int>(std::lround(xy[1] * factor)));
        if (s.coordinate_units != 0) segy_set_field(h.data(), SEGY_TR_COORD_UNITS, s.coordinate_units);
      }
      ASSERT_EQ(segy_write_traceheader(fp, trace, h.data(), s.trace0(), bytes), SEGY_OK);
      const std::vector<char> samples = encoded_trace(layout, i, j, s.ns);
      ASSERT_EQ(segy_writetrace(fp, trace, samples.data(), s.trace0(), bytes), SEGY_OK);
    }
  for (int n = 0; n < s.trailing_placeholders; ++n, ++trace)
    ASSERT_TRUE(write_placeholder(trace));
  ASSERT_EQ(segy_close(fp), SEGY_OK);
}

// segyio's own reading of a post-stack file, told its byte order and where the line numbers are
// (as a segyio user would): every trace decoded by segyio (integers as integers), converted to
// float as any loader does, and placed at the (inline, crossline) its header names, in C order
// [inline][crossline][sample] of ascending line positions. ni and nj come back through the
// pointers.
inline std::vector<float> read_with_segyio(const std::string& path, bool little_endian, int inline_byte,
                                           int crossline_byte, int* ni_out, int* nj_out) {
  std::vector<float> cube;
  segy_file* fp = segy_open(path.c_str(), "rb");
  EXPECT_NE(fp, nullptr);
  if (!fp) return cube;
  if (little_endian) segy_set_format(fp, SEGY_IEEE_FLOAT_4_BYTE | static_cast<int>(SEGY_LSB));
  std::array<char, SEGY_BINARY_HEADER_SIZE> bin{};
  EXPECT_EQ(segy_binheader(fp, bin.data()), SEGY_OK);
  const int format = segy_format(bin.data());
  int ns = segy_samples(bin.data());
  if (ns == 0) { // as segyio's Python reader does: the first trace header's count
    std::array<char, SEGY_TRACE_HEADER_SIZE> first{};
    EXPECT_EQ(segy_traceheader(fp, 0, first.data(), segy_trace0(bin.data()), 0), SEGY_OK);
    segy_get_field(first.data(), SEGY_TR_SAMPLE_COUNT, &ns);
  }
  EXPECT_EQ(segy_set_format(fp, format | (little_endian ? static_cast<int>(SEGY_LSB) : 0)), SEGY_OK);
  const long trace0 = segy_trace0(bin.data());
  const int bytes = segy_trsize(format, ns);
  int traces = 0;
  EXPECT_EQ(segy_traces(fp, &traces, trace0, bytes), SEGY_OK);
  // Line numbers of every trace, then their ranks.
  std::map<int, int> inlines, crosslines;
  std::vector<std::array<int, 2>> lines(static_cast<std::size_t>(traces));
  for (int t = 0; t < traces; ++t) {
    std::array<char, SEGY_TRACE_HEADER_SIZE> h{};
    EXPECT_EQ(segy_traceheader(fp, t, h.data(), trace0, bytes), SEGY_OK);
    std::int32_t il = 0, xl = 0;
    segy_get_field(h.data(), inline_byte, &il);
    segy_get_field(h.data(), crossline_byte, &xl);
    lines[static_cast<std::size_t>(t)] = {il, xl};
    inlines[il] = 0;
    crosslines[xl] = 0;
  }
  int rank = 0;
  for (auto& [number, r] : inlines)
    r = rank++;
  rank = 0;
  for (auto& [number, r] : crosslines)
    r = rank++;
  const auto ni = static_cast<std::size_t>(inlines.size()), nj = static_cast<std::size_t>(crosslines.size());
  *ni_out = static_cast<int>(ni);
  *nj_out = static_cast<int>(nj);
  cube.assign(ni * nj * static_cast<std::size_t>(ns), 0.0f);
  std::vector<char> raw(static_cast<std::size_t>(bytes));
  for (int t = 0; t < traces; ++t) {
    EXPECT_EQ(segy_readtrace(fp, t, raw.data(), trace0, bytes), SEGY_OK);
    EXPECT_EQ(segy_to_native(format, ns, raw.data()), SEGY_OK);
    const auto [il, xl] = lines[static_cast<std::size_t>(t)];
    float* out = cube.data() + (static_cast<std::size_t>(inlines[il]) * nj + static_cast<std::size_t>(crosslines[xl])) *
                                   static_cast<std::size_t>(ns);
    for (int k = 0; k < ns; ++k) {
      const char* p = raw.data() + static_cast<std::size_t>(k) * static_cast<std::size_t>(bytes / ns);
      if (format == SEGY_SIGNED_INTEGER_4_BYTE) {
        std::int32_t v;
        std::memcpy(&v, p, 4);
        out[k] = static_cast<float>(v);
      } else if (format == SEGY_SIGNED_SHORT_2_BYTE) {
        std::int16_t v;
        std::memcpy(&v, p, 2);
        out[k] = static_cast<float>(v);
      } else if (format == SEGY_SIGNED_CHAR_1_BYTE) {
        out[k] = static_cast<float>(static_cast<std::int8_t>(*p));
      } else {
        std::memcpy(&out[k], p, 4);
      }
    }
  }
  segy_close(fp);
  return cube;
}

} // namespace geotandem::volume::testing
