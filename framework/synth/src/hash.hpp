#pragma once
// Counter-based randomness. Every random quantity of a synthetic cube is a hash of the seed, a
// stream tag and integer coordinates, so that it can be computed anywhere, in any order. Only the
// one-time layout of bodies uses a sequential generator (LayoutRng), seeded from the same hash.

#include <cstdint>

namespace geotandem::synth::detail {

// splitmix64 finaliser: a bijection of 64-bit integers with good avalanche.
inline std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Stream tags keep the independent random fields of one seed apart.
enum class Stream : std::uint64_t {
  layout = 1,
  bubbles = 2,
  background = 3,
  reflectors = 4,
  chaotic = 5,
  noise = 6,
  fold = 7,
};

inline std::uint64_t key(std::uint64_t seed, Stream stream) {
  return mix64(seed ^ mix64(static_cast<std::uint64_t>(stream) * 0xd1b54a32d192ed03ULL));
}
inline std::uint64_t hash1(std::uint64_t key, std::int64_t a) {
  return mix64(key ^ static_cast<std::uint64_t>(a));
}
inline std::uint64_t hash2(std::uint64_t key, std::int64_t a, std::int64_t b) {
  return hash1(hash1(key, a), b);
}
inline std::uint64_t hash3(std::uint64_t key, std::int64_t a, std::int64_t b, std::int64_t c) {
  return hash1(hash2(key, a, b), c);
}

// Uniform in [0, 1) from the top 53 bits.
inline double unit(std::uint64_t h) {
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}
// Uniform in [lo, hi).
inline double uniform(std::uint64_t h, double lo, double hi) {
  return lo + (hi - lo) * unit(h);
}

// Sequential generator for the layout (done once, at construction). Platform-independent, unlike
// the standard distributions.
class LayoutRng {
public:
  explicit LayoutRng(std::uint64_t state) : state_(state) {}
  std::uint64_t next() { return mix64(state_ += 0x9e3779b97f4a7c15ULL); }
  double uniform(double lo, double hi) { return detail::uniform(next(), lo, hi); }

private:
  std::uint64_t state_;
};

} // namespace geotandem::synth::detail
