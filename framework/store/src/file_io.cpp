#include "file_io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "geotandem/core/atomic_file.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::store::detail {

std::string errno_text(int error) {
  return std::strerror(error);
}

bool read_at(int fd, void* data, std::size_t size, std::uint64_t offset, const std::filesystem::path& path) {
  auto* bytes = static_cast<char*>(data);
  while (size > 0) {
    ssize_t n = ::pread(fd, bytes, size, static_cast<off_t>(offset));
    if (n < 0) {
      if (errno == EINTR) continue;
      throw IoError("cannot read " + std::to_string(size) + " bytes at offset " + std::to_string(offset) + ": " +
                        errno_text(errno),
                    {path.string()});
    }
    if (n == 0) return false;
    bytes += n;
    size -= static_cast<std::size_t>(n);
    offset += static_cast<std::uint64_t>(n);
  }
  return true;
}

void write_at(int fd, const void* data, std::size_t size, std::uint64_t offset, const std::filesystem::path& path) {
  const auto* bytes = static_cast<const char*>(data);
  while (size > 0) {
    ssize_t n = ::pwrite(fd, bytes, size, static_cast<off_t>(offset));
    if (n < 0) {
      if (errno == EINTR) continue;
      throw IoError("cannot write at offset " + std::to_string(offset) + ": " + errno_text(errno), {path.string()},
                    errno == ENOSPC ? "the disk is full" : "");
    }
    bytes += n;
    size -= static_cast<std::size_t>(n);
    offset += static_cast<std::uint64_t>(n);
  }
}

std::uint64_t file_size(int fd, const std::filesystem::path& path) {
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw IoError("cannot stat: " + errno_text(errno), {path.string()});
  return static_cast<std::uint64_t>(st.st_size);
}

void truncate_file(int fd, std::uint64_t size, const std::filesystem::path& path) {
  while (::ftruncate(fd, static_cast<off_t>(size)) != 0) {
    if (errno == EINTR) continue;
    throw IoError("cannot truncate to " + std::to_string(size) + " bytes: " + errno_text(errno), {path.string()});
  }
}

void sync_data(int fd, const std::filesystem::path& path) {
  while (::fdatasync(fd) != 0) {
    if (errno == EINTR) continue;
    throw IoError("cannot flush to disk (fdatasync): " + errno_text(errno), {path.string()});
  }
}

void sync_directory(const std::filesystem::path& dir) {
  int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw IoError("cannot open directory: " + errno_text(errno), {dir.string()});
  FileHandle handle(fd);
  // Some filesystems refuse fsync on directories (EINVAL); the entry is then as durable as it gets.
  if (::fsync(fd) != 0 && errno != EINVAL)
    throw IoError("cannot flush directory to disk: " + errno_text(errno), {dir.string()});
}

void write_file_atomically(const std::filesystem::path& path, const std::string& text) {
  geotandem::write_file_atomically(path, text, path.filename().string());
}

std::string read_text_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open file: " + errno_text(errno), {path.string()});
  std::stringstream text;
  text << in.rdbuf();
  if (in.bad()) throw IoError("cannot read file", {path.string()});
  return text.str();
}

FileHandle::~FileHandle() {
  if (fd_ >= 0) ::close(fd_);
}

FileHandle& FileHandle::operator=(FileHandle&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

FileHandle open_read(const std::filesystem::path& path) {
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    int error = errno;
    throw IoError("cannot open shard: " + errno_text(error), {path.string()},
                  error == ENOENT ? "the shard file is missing from the store's shards/ directory" : "");
  }
  return FileHandle(fd);
}

} // namespace geotandem::store::detail
