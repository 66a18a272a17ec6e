#pragma once
// SEG-Y files written through segyio's C API (not through our writer), with known line numbers,
// coordinates and samples, and the defects the tests need (missing, swapped or shuffled traces,
// gaps, extended headers). Shared by segy_test.cpp and segy_broken_test.cpp.

#include <gtest/gtest.h>
#include <segyio/segy.h>

#include <algorithm>
#include <array>
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

  long trace0() const { return 3600L + 3200L * extended_headers; }
  int inline_number(int i) const { return il0 + (i + (gap_in_inlines && i >= ni / 2 ? 1 : 0)) * il_step; }
};

inline double stored_factor(int scalar) {
  return scalar == 0 ? 1.0 : scalar > 0 ? 1.0 / scalar : -scalar;
}

inline void write_with_segyio(const std::string& path, const SegySpec& s) {
  segy_file* fp = segy_open(path.c_str(), "w+b");
  ASSERT_NE(fp, nullptr);
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
  // Unsupported codes are laid out as 4-byte IEEE: only the code in the binary header matters.
  const int layout = s.format == SEGY_SIGNED_SHORT_2_BYTE ? SEGY_IEEE_FLOAT_4_BYTE : s.format;
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
  for (const auto& [i, j] : order)
    for (int offset = 1; offset <= s.offsets; ++offset, ++trace) {
      std::array<char, SEGY_TRACE_HEADER_SIZE> h{};
      segy_set_field(h.data(), SEGY_TR_INLINE, s.inline_number(i));
      segy_set_field(h.data(), SEGY_TR_CROSSLINE, s.xl0 + j * s.xl_step);
      segy_set_field(h.data(), SEGY_TR_OFFSET, offset);
      segy_set_field(h.data(), SEGY_TR_SAMPLE_COUNT, s.ns);
      segy_set_field(h.data(), SEGY_TR_SAMPLE_INTER, s.interval_us);
      segy_set_field(h.data(), SEGY_TR_DELAY_REC_TIME, s.delay_ms);
      if (s.coordinates) {
        auto xy = s.affine.apply(i, j);
        segy_set_field(h.data(), SEGY_TR_SOURCE_GROUP_SCALAR, s.scalar);
        segy_set_field(h.data(), SEGY_TR_CDP_X, static_cast<int>(std::lround(xy[0] * factor)));
        segy_set_field(h.data(), SEGY_TR_CDP_Y, static_cast<int>(std::lround(xy[1] * factor)));
      }
      ASSERT_EQ(segy_write_traceheader(fp, trace, h.data(), s.trace0(), bytes), SEGY_OK);
      std::vector<float> samples(static_cast<std::size_t>(s.ns));
      for (int k = 0; k < s.ns; ++k)
        samples[static_cast<std::size_t>(k)] = formula(i, j, k);
      segy_from_native(layout, s.ns, samples.data());
      ASSERT_EQ(segy_writetrace(fp, trace, samples.data(), s.trace0(), bytes), SEGY_OK);
    }
  ASSERT_EQ(segy_close(fp), SEGY_OK);
}

} // namespace geotandem::volume::testing
