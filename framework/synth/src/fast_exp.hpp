#pragma once
// exp(y) in straight-line double arithmetic, so that a loop over many arguments vectorises (the
// C library's exp is a call per value). Also independent of the C library's version.
//
// Method: y = n ln 2 + r with |r| <= ln 2 / 2 (Cody-Waite split of ln 2), e^r by its Taylor series
// to degree 13 (truncation below 2e-16 relative), times 2^n assembled in the exponent bits.
// Accuracy: within 4e-16 relative of exp(y) for y in [-700, 700]; arguments are clamped to that
// range, so exp(-1000) gives about 1e-304 rather than 0.

#include <array>
#include <bit>
#include <cstdint>

namespace geotandem::synth::detail {

inline double fast_exp(double y) {
  constexpr double log2e = 1.4426950408889634;
  constexpr double ln2_hi = 0.6931471803691238; // ln 2 to 32 significant bits: n * ln2_hi is exact
  constexpr double ln2_lo = 1.9082149292705877e-10;
  constexpr double shifter = 6755399441055744.0; // 1.5 * 2^52: adding it rounds to an integer
  const double yc = y < -700.0 ? -700.0 : (y > 700.0 ? 700.0 : y);
  const double k = yc * log2e + shifter;
  const double n = k - shifter;
  const double r = (yc - n * ln2_hi) - n * ln2_lo;
  // The Taylor coefficients 1/m!, summed by Estrin's scheme: a tree of depth 5 rather than a chain
  // of 13 dependent steps (the vectorised loops over spikes waited on that chain).
  constexpr auto c = [] {
    std::array<double, 14> t{};
    t[0] = 1.0;
    for (int m = 1; m < 14; ++m)
      t[m] = t[m - 1] / m;
    return t;
  }();
  const double r2 = r * r, r4 = r2 * r2, r8 = r4 * r4;
  const double p01 = c[0] + c[1] * r, p23 = c[2] + c[3] * r, p45 = c[4] + c[5] * r, p67 = c[6] + c[7] * r;
  const double p89 = c[8] + c[9] * r, p1011 = c[10] + c[11] * r, p1213 = c[12] + c[13] * r;
  const double q03 = p01 + p23 * r2, q47 = p45 + p67 * r2, q811 = p89 + p1011 * r2;
  const double p = (q03 + q47 * r4) + (q811 + p1213 * r4) * r8;
  // The low bits of k hold n; (n + 1023) << 52 is 2^n.
  const std::uint64_t scale_bits = (std::bit_cast<std::uint64_t>(k) + 1023u) << 52;
  return p * std::bit_cast<double>(scale_bits);
}

} // namespace geotandem::synth::detail
