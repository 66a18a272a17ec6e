#pragma once
// The seismic kind's white noise (seismic.cpp).

#include <cstdint>

namespace geotandem::synth::detail {

// Unit-variance white noise (uniform in [-sqrt 3, sqrt 3)) at samples k0 .. k0 + n of the trace
// whose stream is `trace_key`: out[k - k0] is uniform(hash1(trace_key, k), -sqrt 3, sqrt 3) drawn
// in double precision (hash.hpp; the stream the generator has always drawn), rounded to a float.
void white_noise(std::uint64_t trace_key, std::int64_t k0, std::int64_t n, float* out);

} // namespace geotandem::synth::detail
