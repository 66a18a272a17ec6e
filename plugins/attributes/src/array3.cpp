// The spare storage of Array3 (array3.hpp): per thread, the largest few arrays freed, for the next
// ones of about their size.
#include "array3.hpp"

#include <algorithm>
#include <vector>

namespace geotandem::attributes::detail {

namespace {

// The quickstart's chain (chaos x normalised envelope) holds at most three large arrays at once:
// the product's second input, the envelope's mirrored input box, and its filtered copy or (at the
// cube's faces, while the box is mirrored) the part of the box inside the cube.
constexpr std::size_t kSpares = 3;

struct Spare {
  float* data;
  std::size_t capacity;
};

struct Spares {
  std::vector<Spare> kept;
  void clear() {
    for (const Spare& s : kept)
      delete[] s.data;
    kept.clear();
  }
  ~Spares() { clear(); }
};

thread_local Spares spares;

} // namespace

void ArrayStorageRelease::operator()(float* data) const noexcept {
  if (!data) return;
  if (capacity < kReusedFloats) {
    delete[] data;
    return;
  }
  std::vector<Spare>& kept = spares.kept;
  if (kept.size() < kSpares) {
    try {
      kept.push_back({data, capacity});
      return;
    } catch (...) {
      delete[] data; // no room to remember it: freed as without the spares
      return;
    }
  }
  // Full: it replaces the smallest spare when it is larger.
  auto smallest = std::min_element(kept.begin(), kept.end(),
                                   [](const Spare& a, const Spare& b) { return a.capacity < b.capacity; });
  if (smallest->capacity < capacity) {
    delete[] smallest->data;
    *smallest = {data, capacity};
    return;
  }
  delete[] data;
}

ArrayStorage take_array_storage(std::size_t count) {
  if (count >= kReusedFloats) {
    std::vector<Spare>& kept = spares.kept;
    auto best = kept.end();
    for (auto it = kept.begin(); it != kept.end(); ++it)
      if (it->capacity >= count && it->capacity / 2 <= count && (best == kept.end() || it->capacity < best->capacity))
        best = it;
    if (best != kept.end()) {
      const Spare s = *best;
      kept.erase(best);
      return ArrayStorage(s.data, ArrayStorageRelease{s.capacity});
    }
  }
  return ArrayStorage(new float[count], ArrayStorageRelease{count});
}

void release_spare_arrays() {
  spares.clear();
}

std::size_t spare_array_bytes() {
  std::size_t bytes = 0;
  for (const Spare& s : spares.kept)
    bytes += s.capacity * sizeof(float);
  return bytes;
}

} // namespace geotandem::attributes::detail
