#pragma once
// Tests that forge working-surface records (issue 52): where a record's sections start
// (docs/algorithm.md, "The wire format"), read and write its fields, and make its header's length
// and XXH64 right again after an edit, as a forger who knows the format would.
#include <xxhash.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "geotandem/tandem/serialize.hpp"

namespace geotandem::testing {

using RecordBytes = std::vector<std::byte>;

template <class T> T record_get(const RecordBytes& r, std::size_t at) {
  T v;
  std::memcpy(&v, r.data() + at, sizeof(T));
  return v;
}
template <class T> void record_put(RecordBytes& r, std::size_t at, T v) {
  std::memcpy(r.data() + at, &v, sizeof(T));
}

// The length and checksum of the header made right again for the payload as it now is.
inline void reseal(RecordBytes& r) {
  const std::uint64_t length = r.size() - tandem::kSurfaceWireHeaderSize;
  const std::uint64_t hash = XXH64(r.data() + tandem::kSurfaceWireHeaderSize, length, 0);
  record_put(r, 16, length);
  record_put(r, 24, hash);
}

// Offsets of the sections of a record of version 5, found by walking its counts.
struct RecordLayout {
  static constexpr std::size_t kVertex = 145, kTriangle = 12, kEdge = 46;
  static constexpr std::size_t kLatticeId = 128, kComponent = 136; // within a vertex
  std::size_t axis = 0, blocks_count = 0, blocks = 0, front = 0, components_count = 0, components = 0;
  std::size_t vertices_count = 0, vertices = 0, triangles_count = 0, triangles = 0, edges_count = 0, edges = 0;
  std::size_t nb = 0, nc = 0, nv = 0, nt = 0, ne = 0;

  explicit RecordLayout(const RecordBytes& r) {
    std::size_t at = tandem::kSurfaceWireHeaderSize + 24 + 48 + 1 + 48; // shape, spacing, unit, affine
    axis = at;
    at += 4 + 8 + 8 + 1 + 8 + 48; // axis, E0, alpha, flags, compaction, region cube
    blocks_count = at;
    nb = record_get<std::uint64_t>(r, at);
    blocks = at + 8;
    front = blocks + 48 * nb;
    components_count = front + 8 + 8 + 24 + 8 * 14; // front, last rank, origin, counters
    nc = record_get<std::uint64_t>(r, components_count);
    components = components_count + 8;
    vertices_count = components + 8 * nc;
    nv = record_get<std::uint64_t>(r, vertices_count);
    vertices = vertices_count + 8;
    triangles_count = vertices + kVertex * nv;
    nt = record_get<std::uint64_t>(r, triangles_count);
    triangles = triangles_count + 8;
    edges_count = triangles + kTriangle * nt;
    ne = record_get<std::uint64_t>(r, edges_count);
    edges = edges_count + 8;
  }
  std::size_t vertex(std::size_t i) const { return vertices + kVertex * i; }
  std::size_t corner(std::size_t t, std::size_t c) const { return triangles + kTriangle * t + 4 * c; }
  std::size_t edge(std::size_t e) const { return edges + kEdge * e; }
};

} // namespace geotandem::testing
