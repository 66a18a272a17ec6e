#pragma once
// exp(y) in straight-line double arithmetic, so that a loop over many arguments vectorises (the
// C library's exp is a call per value). Also independent of the C library's version.
//
// Method: y = n ln 2 + r with |r| <= ln 2 / 2 (Cody-Waite split of ln 2), e^r by its Taylor series
// to degree 13 (truncation below 2e-16 relative), times 2^n assembled in the exponent bits.
// Accuracy: within 4e-16 relative of exp(y) for y in [-700, 700]; arguments are clamped to that
// range, so exp(-1000) gives about 1e-304 rather than 0.

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
  // Horner: 1 + r (1 + r/2 (1 + r/3 (... (1 + r/13)))).
  double p = 1.0;
#pragma GCC unroll 13
  for (int m = 13; m >= 1; --m)
    p = 1.0 + p * r * (1.0 / m);
  // The low bits of k hold n; (n + 1023) << 52 is 2^n.
  const std::uint64_t scale_bits = (std::bit_cast<std::uint64_t>(k) + 1023u) << 52;
  return p * std::bit_cast<double>(scale_bits);
}

} // namespace geotandem::synth::detail
