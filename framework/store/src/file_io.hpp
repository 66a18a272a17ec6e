#pragma once
// POSIX file helpers for shards and exports: full reads and writes at an offset, durable syncs,
// and atomic replacement of small files. Every failure is an IoError naming the file.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace geotandem::store::detail {

// Reads exactly `size` bytes at `offset`; returns false when the file ends first.
bool read_at(int fd, void* data, std::size_t size, std::uint64_t offset, const std::filesystem::path& path);
void write_at(int fd, const void* data, std::size_t size, std::uint64_t offset, const std::filesystem::path& path);
std::uint64_t file_size(int fd, const std::filesystem::path& path);
void truncate_file(int fd, std::uint64_t size, const std::filesystem::path& path);
void sync_data(int fd, const std::filesystem::path& path);
// Makes a directory entry (a new or renamed file) durable.
void sync_directory(const std::filesystem::path& dir);
// Writes `text` to a unique temporary beside `path` (.NAME.XXXXXX.tmp), syncs it and renames it
// over `path` (geotandem::AtomicFile).
void write_file_atomically(const std::filesystem::path& path, const std::string& text);
std::string read_text_file(const std::filesystem::path& path);
std::string errno_text(int error);

// An owned file descriptor.
class FileHandle {
public:
  FileHandle() = default;
  explicit FileHandle(int fd) : fd_(fd) {}
  ~FileHandle();
  FileHandle(FileHandle&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  FileHandle& operator=(FileHandle&& other) noexcept;
  FileHandle(const FileHandle&) = delete;
  FileHandle& operator=(const FileHandle&) = delete;
  int get() const { return fd_; }
  int release() {
    int fd = fd_;
    fd_ = -1;
    return fd;
  }

private:
  int fd_ = -1;
};

// Opens read-only; throws IoError naming the file.
FileHandle open_read(const std::filesystem::path& path);

} // namespace geotandem::store::detail
