#include "record.hpp"

#include <xxhash.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <memory>
#include <new>

#include "file_io.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::store::detail {
namespace {

template <class T> void put(char*& out, T value) {
  std::memcpy(out, &value, sizeof(T));
  out += sizeof(T);
}

template <class T> T get(const char* in) {
  T value;
  std::memcpy(&value, in, sizeof(T));
  return value;
}

struct HashState {
  XXH64_state_t* state = XXH64_createState();
  HashState() {
    if (!state) throw std::bad_alloc();
    XXH64_reset(state, 0);
  }
  ~HashState() { XXH64_freeState(state); }
  HashState(const HashState&) = delete;
  HashState& operator=(const HashState&) = delete;
};

} // namespace

std::optional<std::uint64_t> record_length(std::uint64_t vertex_count, std::uint64_t triangle_count) {
  constexpr auto max = std::numeric_limits<std::uint64_t>::max();
  if (vertex_count > max / 64 || triangle_count > max / 64) return std::nullopt;
  return record_header_size + record_trailer_size + 24 * vertex_count + 12 * triangle_count;
}

std::vector<char> encode_record(std::uint64_t key, const mesh::SurfaceMesh& surface) {
  if (surface.triangles.empty() || surface.points.empty())
    throw InvalidArgument("component " + std::to_string(key) + " has an empty surface; nothing to store");
  if (surface.points.size() >= std::numeric_limits<std::uint32_t>::max())
    throw InvalidArgument("component " + std::to_string(key) + " has " + std::to_string(surface.points.size()) +
                          " vertices; a record holds at most 2^32 - 2");
  const auto vertex_count = static_cast<std::uint32_t>(surface.points.size());
  for (std::size_t t = 0; t < surface.triangles.size(); ++t)
    for (auto v : surface.triangles[t])
      if (v >= vertex_count)
        throw InvalidArgument("component " + std::to_string(key) + ": triangle " + std::to_string(t) +
                              " names vertex " + std::to_string(v) + " of " + std::to_string(vertex_count));
  const std::uint64_t length = *record_length(surface.points.size(), surface.triangles.size());
  std::vector<char> record(length);
  char* out = record.data();
  std::memcpy(out, record_magic.data(), record_magic.size());
  out += record_magic.size();
  put(out, record_version);
  put(out, record_header_size);
  put(out, key);
  put(out, static_cast<std::uint64_t>(surface.points.size()));
  put(out, static_cast<std::uint64_t>(surface.triangles.size()));
  put(out, std::uint64_t{0});
  // Point and Triangle are plain arrays of double and uint32: their memory is already the layout.
  static_assert(sizeof(mesh::Point) == 24 && sizeof(mesh::Triangle) == 12);
  std::memcpy(out, surface.points.data(), surface.points.size() * sizeof(mesh::Point));
  out += surface.points.size() * sizeof(mesh::Point);
  std::memcpy(out, surface.triangles.data(), surface.triangles.size() * sizeof(mesh::Triangle));
  out += surface.triangles.size() * sizeof(mesh::Triangle);
  put(out, record_checksum(record.data(), length));
  return record;
}

std::optional<RecordHeader> parse_header(const char* bytes) {
  if (std::memcmp(bytes, record_magic.data(), record_magic.size()) != 0) return std::nullopt;
  if (get<std::uint16_t>(bytes + 4) != record_version) return std::nullopt;
  if (get<std::uint16_t>(bytes + 6) != record_header_size) return std::nullopt;
  RecordHeader header;
  header.key = get<std::uint64_t>(bytes + 8);
  header.vertex_count = get<std::uint64_t>(bytes + 16);
  header.triangle_count = get<std::uint64_t>(bytes + 24);
  if (!record_length(header.vertex_count, header.triangle_count)) return std::nullopt;
  return header;
}

std::uint64_t record_checksum(const char* record, std::uint64_t length) {
  return XXH64(record, static_cast<std::size_t>(length - record_trailer_size), 0);
}

std::uint64_t record_checksum(const char* header, const mesh::SurfaceMesh& surface) {
  std::unique_ptr<XXH64_state_t, XXH_errorcode (*)(XXH64_state_t*)> state(XXH64_createState(), XXH64_freeState);
  if (!state) throw std::bad_alloc();
  XXH64_reset(state.get(), 0);
  XXH64_update(state.get(), header, record_header_size);
  XXH64_update(state.get(), surface.points.data(), surface.points.size() * sizeof(mesh::Point));
  XXH64_update(state.get(), surface.triangles.data(), surface.triangles.size() * sizeof(mesh::Triangle));
  return XXH64_digest(state.get());
}

std::optional<std::uint64_t> verify_record_at(int fd, std::uint64_t offset, std::uint64_t size,
                                              const std::filesystem::path& path) {
  if (size < offset || size - offset < record_header_size + record_trailer_size) return std::nullopt;
  char head[record_header_size];
  if (!read_at(fd, head, sizeof head, offset, path)) return std::nullopt;
  auto header = parse_header(head);
  if (!header) return std::nullopt;
  const std::uint64_t length = *record_length(header->vertex_count, header->triangle_count);
  if (size - offset < length) return std::nullopt;
  HashState hash;
  XXH64_update(hash.state, head, sizeof head);
  std::vector<char> chunk(std::min<std::uint64_t>(length, 1u << 20));
  std::uint64_t position = offset + record_header_size;
  const std::uint64_t payload_end = offset + length - record_trailer_size;
  while (position < payload_end) {
    auto n = static_cast<std::size_t>(std::min<std::uint64_t>(chunk.size(), payload_end - position));
    if (!read_at(fd, chunk.data(), n, position, path)) return std::nullopt;
    XXH64_update(hash.state, chunk.data(), n);
    position += n;
  }
  std::uint64_t stored = 0;
  if (!read_at(fd, &stored, sizeof stored, payload_end, path)) return std::nullopt;
  if (stored != XXH64_digest(hash.state)) return std::nullopt;
  return length;
}

} // namespace geotandem::store::detail
