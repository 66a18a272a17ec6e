#pragma once
// The byte layout of one shard record (docs/store-format.md), little-endian:
//   0  magic "GTCR" (4 bytes)
//   4  uint16 record format version (1)
//   6  uint16 header size in bytes (40)
//   8  uint64 component key
//  16  uint64 vertex count V
//  24  uint64 triangle count T
//  32  uint64 flags (0; reserved)
//  40  V x 3 float64 world x, y, z
//      T x 3 uint32 vertex indices (0-based)
//      uint64 xxh64 (seed 0) of every byte above
// Record length = 48 + 24 V + 12 T.

#include <array>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "geotandem/mesh/surface.hpp"
#include "geotandem/store/shard.hpp"

namespace geotandem::store::detail {

static_assert(std::endian::native == std::endian::little,
              "shard records are little-endian; a big-endian port must byte-swap them");

inline constexpr std::array<char, 4> record_magic{'G', 'T', 'C', 'R'};
inline constexpr std::uint16_t record_version = 1;
inline constexpr std::uint16_t record_header_size = 40;
inline constexpr std::uint64_t record_trailer_size = 8;

struct RecordHeader {
  std::uint64_t key = 0;
  std::uint64_t vertex_count = 0;
  std::uint64_t triangle_count = 0;
};

// Record length for the given counts, or nullopt when it would overflow 64 bits.
std::optional<std::uint64_t> record_length(std::uint64_t vertex_count, std::uint64_t triangle_count);

// Serialises a whole record (header, payload, checksum). Throws InvalidArgument for an empty
// surface, more than 2^32 - 1 vertices or a triangle naming a missing vertex.
std::vector<char> encode_record(std::uint64_t key, const mesh::SurfaceMesh& world_surface);

// Parses a header; nullopt when the magic, version or header size is wrong.
std::optional<RecordHeader> parse_header(const char* bytes);

// xxh64 of bytes [0, length - 8) of an encoded record held in memory.
std::uint64_t record_checksum(const char* record, std::uint64_t length);
// The same checksum for a record held as its header and the surface it decodes to.
std::uint64_t record_checksum(const char* header, const mesh::SurfaceMesh& surface);

// Checks the record starting at `offset` of an open shard of `size` bytes: complete, header valid,
// checksum right. Returns its length, or nullopt when it is torn or damaged. Reads in chunks.
std::optional<std::uint64_t> verify_record_at(int fd, std::uint64_t offset, std::uint64_t size,
                                              const std::filesystem::path& path);

// read_record on an already open shard (the store keeps shards open across reads).
mesh::SurfaceMesh read_record_from(int fd, const std::filesystem::path& shard_file, const RecordLocation& location,
                                   std::uint64_t key);

} // namespace geotandem::store::detail
