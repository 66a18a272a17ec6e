#pragma once
// Raw data shards: append-only files of component records (docs/store-format.md). Each writer
// process owns one shard, `STORE/shards/<writer>.gts`, so that workers on a shared filesystem never
// write the same file. A record holds one component in world coordinates and ends with an xxh64
// checksum of everything before it.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "geotandem/mesh/component.hpp"
#include "geotandem/volume/geometry.hpp"

namespace geotandem::store {

// Where one record lives and what it holds; the index stores exactly this.
struct RecordLocation {
  std::string shard;          // writer name: the file is shards/<shard>.gts
  std::uint64_t offset = 0;   // byte offset of the record in the shard
  std::uint64_t length = 0;   // bytes, checksum included
  std::uint64_t checksum = 0; // xxh64 of the record's header and payload
  std::uint64_t vertex_count = 0;
  std::uint64_t triangle_count = 0;
  bool operator==(const RecordLocation&) const = default;
};

// Writer names become file names: 1 to 64 characters from [A-Za-z0-9._-], not starting with '.'.
// Throws InvalidArgument otherwise.
void validate_writer_name(const std::string& writer);

// The path of a writer's shard in a store directory.
std::filesystem::path shard_path(const std::filesystem::path& store_dir, const std::string& writer);

struct ShardWriterOptions {
  // Where the shard's valid content ends, when the caller knows it (the single process of a local
  // run knows it from the index: the end of its last indexed record). The file is truncated there,
  // dropping a torn tail and records that were never indexed. Unset: the writer walks the records
  // from the start, verifying each checksum, and truncates after the last valid one (workers do
  // this; they never read the index).
  std::optional<std::uint64_t> valid_end;
  // fdatasync the shard in sync() (off only for benchmarks measuring its cost).
  bool durable = true;
};

// Appends records to one shard. Holds an exclusive lock on the file (flock) while open, so a second
// writer with the same name fails instead of interleaving records. Not thread-safe.
class ShardWriter {
public:
  // Opens or creates STORE/shards/<writer>.gts. `geometry` maps the index coordinates of appended
  // components to world coordinates (use the store's geometry). Throws InvalidArgument for a bad
  // writer name, IoError when the file cannot be opened or is locked by another writer, FormatError
  // when `valid_end` lies beyond the end of the file (records the index knows of are missing).
  ShardWriter(const std::filesystem::path& store_dir, const std::string& writer, const volume::Geometry& geometry,
              ShardWriterOptions options = {});
  ~ShardWriter();
  ShardWriter(ShardWriter&& other) noexcept;
  ShardWriter& operator=(ShardWriter&&) = delete;
  ShardWriter(const ShardWriter&) = delete;

  // Converts the component's surface to world coordinates (mesh::to_world) and appends its record.
  // The returned location may be handed to the index only after sync() has returned.
  // Throws InvalidArgument for an empty surface or a triangle naming a missing vertex, IoError when
  // the write fails (the shard is then cut back to its previous end).
  RecordLocation append(const mesh::Component& component);
  // Appends a surface already in world coordinates.
  RecordLocation append_world(std::uint64_t key, const mesh::SurfaceMesh& world_surface);
  // Makes every appended record durable (fdatasync). Throws IoError.
  void sync();

  const std::string& writer() const { return writer_; }
  const std::filesystem::path& path() const { return path_; }
  std::uint64_t end() const { return end_; }
  // Bytes dropped from the tail when the shard was opened (a torn or unindexed tail), for logs.
  std::uint64_t dropped_bytes() const { return dropped_; }

private:
  int fd_ = -1;
  std::string writer_;
  std::filesystem::path path_;
  volume::Geometry geometry_;
  ShardWriterOptions options_;
  std::uint64_t end_ = 0;
  std::uint64_t dropped_ = 0;
};

// Reads and verifies the record at `location` in `shard_file`, returning its world surface.
// Throws IoError when the file cannot be read, FormatError naming shard, offset and key when the
// record is truncated, has a bad magic, version or checksum, or disagrees with `location` or `key`.
mesh::SurfaceMesh read_record(const std::filesystem::path& shard_file, const RecordLocation& location,
                              std::uint64_t key);

} // namespace geotandem::store
