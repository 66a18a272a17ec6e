#pragma once
// Benchmarks that measure reads from disk ("cold") drop a file's pages from the page cache first.

#include <fcntl.h>
#include <unistd.h>

#include <filesystem>
#include <vector>

namespace geotandem::bench {

// `path` itself when it is a file; the files under it when it is a directory (a Zarr store).
inline std::vector<std::filesystem::path> files_of(const std::filesystem::path& path) {
  if (std::filesystem::is_regular_file(path)) return {path};
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(path))
    if (entry.is_regular_file()) files.push_back(entry.path());
  return files;
}

// Drops the pages of every file of `path` from the page cache (fdatasync, then posix_fadvise
// DONTNEED); false if the kernel refused.
inline bool evict(const std::filesystem::path& path) {
  bool ok = true;
  for (const auto& file : files_of(path)) {
    const int fd = ::open(file.c_str(), O_RDONLY);
    if (fd < 0) return false;
    ::fdatasync(fd);
    ok = ::posix_fadvise(fd, 0, 0, POSIX_FADV_DONTNEED) == 0 && ok;
    ::close(fd);
  }
  return ok;
}

} // namespace geotandem::bench
