// Shard writer and record reader. Crash safety rests on three facts: a record is appended past
// the shard's last valid record with one pwrite; it is made durable (fdatasync) before anybody
// indexes it; and a writer reopening a shard cuts off whatever follows the last valid record.

#include "geotandem/store/shard.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>

#include "file_io.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/mesh/measure.hpp"
#include "record.hpp"

namespace geotandem::store {

using namespace detail;

void validate_writer_name(const std::string& writer) {
  bool ok = !writer.empty() && writer.size() <= 64 && writer.front() != '.';
  for (char c : writer)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-')) ok = false;
  if (!ok)
    throw InvalidArgument("invalid shard writer name '" + writer + "'", {},
                          "use 1 to 64 characters from A-Z a-z 0-9 . _ - , not starting with '.'");
}

std::filesystem::path shard_path(const std::filesystem::path& store_dir, const std::string& writer) {
  validate_writer_name(writer);
  return store_dir / "shards" / (writer + ".gts");
}

ShardWriter::ShardWriter(const std::filesystem::path& store_dir, const std::string& writer,
                         const volume::Geometry& geometry, ShardWriterOptions options)
    : writer_(writer), path_(shard_path(store_dir, writer)), geometry_(geometry), options_(options) {
  const auto dir = path_.parent_path();
  if (!std::filesystem::is_directory(dir))
    throw IoError("the store has no shards/ directory", {dir.string()}, "is this a geotandem store?");
  const bool existed = std::filesystem::exists(path_);
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw IoError("cannot open shard for writing: " + errno_text(errno), {path_.string()});
  FileHandle guard(fd_);
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    int error = errno;
    if (error == EWOULDBLOCK)
      throw IoError("shard is locked by another writer: another process is extracting into this store",
                    {path_.string()},
                    "wait until it ends, then run again to resume; or write to another output directory");
    throw IoError("cannot lock shard: " + errno_text(error), {path_.string()});
  }
  if (!existed) sync_directory(dir);
  const std::uint64_t size = file_size(fd_, path_);
  if (options_.valid_end) {
    if (*options_.valid_end > size)
      throw FormatError("shard holds " + std::to_string(size) + " bytes but the index has records up to byte " +
                            std::to_string(*options_.valid_end),
                        {path_.string()}, "the shard was truncated or replaced; indexed components are lost");
    end_ = *options_.valid_end;
  } else {
    // Walk the records from the start; the first one that is torn or damaged ends the valid part.
    std::uint64_t offset = 0;
    while (offset < size) {
      auto length = verify_record_at(fd_, offset, size, path_);
      if (!length) break;
      offset += *length;
    }
    end_ = offset;
  }
  dropped_ = size - end_;
  if (dropped_ > 0) {
    truncate_file(fd_, end_, path_);
    if (options_.durable) sync_data(fd_, path_);
  }
  guard.release();
}

ShardWriter::~ShardWriter() {
  if (fd_ >= 0) ::close(fd_); // also releases the flock
}

ShardWriter::ShardWriter(ShardWriter&& other) noexcept
    : fd_(other.fd_), writer_(std::move(other.writer_)), path_(std::move(other.path_)), geometry_(other.geometry_),
      options_(other.options_), end_(other.end_), dropped_(other.dropped_) {
  other.fd_ = -1;
}

RecordLocation ShardWriter::append(const mesh::Component& component) {
  if (component.surface.empty())
    throw InvalidArgument("component " + std::to_string(component.key) + " has an empty surface; nothing to store");
  return append_world(component.key, mesh::to_world(component.surface, geometry_));
}

RecordLocation ShardWriter::append_world(std::uint64_t key, const mesh::SurfaceMesh& world_surface) {
  const auto record = encode_record(key, world_surface);
  try {
    write_at(fd_, record.data(), record.size(), end_, path_);
  } catch (const IoError&) {
    // Leave no partial record behind: the next append starts at the old end.
    if (::ftruncate(fd_, static_cast<off_t>(end_)) != 0) {
      // The write error is the one to report; a failed cut leaves a tail the next open drops.
    }
    throw;
  }
  RecordLocation location;
  location.shard = writer_;
  location.offset = end_;
  location.length = record.size();
  std::memcpy(&location.checksum, record.data() + record.size() - record_trailer_size, sizeof(std::uint64_t));
  location.vertex_count = world_surface.points.size();
  location.triangle_count = world_surface.triangles.size();
  end_ += record.size();
  return location;
}

void ShardWriter::sync() {
  if (options_.durable) sync_data(fd_, path_);
}

mesh::SurfaceMesh read_record(const std::filesystem::path& shard_file, const RecordLocation& location,
                              std::uint64_t key) {
  auto file = open_read(shard_file);
  return detail::read_record_from(file.get(), shard_file, location, key);
}

mesh::SurfaceMesh detail::read_record_from(int fd, const std::filesystem::path& shard_file,
                                           const RecordLocation& location, std::uint64_t key) {
  auto fail = [&](const std::string& what) -> FormatError {
    return FormatError("record of component " + std::to_string(key) + " at offset " + std::to_string(location.offset) +
                           ": " + what,
                       {shard_file.string()},
                       "the shard is damaged; 'geotandem store check' lists the damaged components, rerunning the same "
                       "extraction into the store writes them again, 'store export --skip-damaged' exports the others");
  };
  auto expected = record_length(location.vertex_count, location.triangle_count);
  if (!expected || *expected != location.length) throw fail("the index's length and counts disagree");
  // Read straight into the surface's arrays (the record's payload is their memory layout): no
  // copy of the whole record is held, faulted in and copied again.
  const auto truncated = [&] { return fail("the shard ends before the record does (truncated)"); };
  char header_bytes[record_header_size];
  if (!read_at(fd, header_bytes, sizeof header_bytes, location.offset, shard_file)) throw truncated();
  auto header = parse_header(header_bytes);
  if (!header) throw fail("bad record header (magic, version or size)");
  if (header->key != key) throw fail("the record holds key " + std::to_string(header->key));
  if (header->vertex_count != location.vertex_count || header->triangle_count != location.triangle_count)
    throw fail("the record's counts disagree with the index");
  static_assert(sizeof(mesh::Point) == 24 && sizeof(mesh::Triangle) == 12, "the records' payload layout");
  mesh::SurfaceMesh surface;
  surface.points.resize(header->vertex_count);
  surface.triangles.resize(header->triangle_count);
  const std::uint64_t points_bytes = surface.points.size() * sizeof(mesh::Point),
                      triangles_bytes = surface.triangles.size() * sizeof(mesh::Triangle);
  std::uint64_t at = location.offset + record_header_size, stored = 0;
  if (!read_at(fd, surface.points.data(), points_bytes, at, shard_file) ||
      !read_at(fd, surface.triangles.data(), triangles_bytes, at + points_bytes, shard_file) ||
      !read_at(fd, &stored, sizeof stored, at + points_bytes + triangles_bytes, shard_file))
    throw truncated();
  if (stored != record_checksum(header_bytes, surface) || stored != location.checksum) throw fail("checksum mismatch");
  for (const auto& triangle : surface.triangles)
    for (auto v : triangle)
      if (v >= surface.points.size()) throw fail("a triangle names a missing vertex");
  return surface;
}

} // namespace geotandem::store
