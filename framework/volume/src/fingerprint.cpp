#include "geotandem/volume/fingerprint.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace geotandem::volume {
namespace {

// FNV-1a, 64 bits: enough to tell two cubes apart, no dependency.
std::uint64_t mix(std::uint64_t hash, const unsigned char* data, std::size_t size) {
  for (std::size_t n = 0; n < size; ++n) {
    hash ^= data[n];
    hash *= 1099511628211ULL;
  }
  return hash;
}

std::uint64_t sample_file(const std::filesystem::path& path, std::uint64_t size, std::uint64_t hash) {
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return hash;
  std::vector<unsigned char> buffer(std::size_t{64} * 1024);
  auto take = [&](std::uint64_t offset, std::size_t length) {
    ssize_t got = ::pread(fd, buffer.data(), length, static_cast<off_t>(offset));
    if (got > 0) hash = mix(hash, buffer.data(), static_cast<std::size_t>(got));
  };
  take(0, buffer.size());
  constexpr std::uint64_t blocks = 62, block = 4096;
  if (size > 2 * buffer.size())
    for (std::uint64_t b = 1; b <= blocks; ++b)
      take(size / (blocks + 1) * b, block);
  if (size > buffer.size()) take(size - std::min<std::uint64_t>(size, buffer.size()), buffer.size());
  ::close(fd);
  return hash;
}

std::string hex(std::uint64_t value) {
  char text[20];
  std::snprintf(text, sizeof text, "%016" PRIx64, value);
  return text;
}

} // namespace

nlohmann::json input_fingerprint(const std::string& source) {
  struct stat info = {};
  if (::stat(source.c_str(), &info) != 0 || !(S_ISREG(info.st_mode) || S_ISDIR(info.st_mode)))
    return {{"description", source}};
  std::uint64_t hash = 14695981039346656037ULL, size = 0;
  std::int64_t newest = 0;
  auto add = [&](const std::filesystem::path& file, const struct stat& s) {
    hash = sample_file(file, static_cast<std::uint64_t>(s.st_size), hash);
    size += static_cast<std::uint64_t>(s.st_size);
    newest =
        std::max<std::int64_t>(newest, static_cast<std::int64_t>(s.st_mtim.tv_sec) * 1000000000 + s.st_mtim.tv_nsec);
  };
  if (S_ISREG(info.st_mode)) {
    add(source, info);
  } else {
    std::error_code ec;
    std::vector<std::filesystem::path> files;
    for (auto it = std::filesystem::recursive_directory_iterator(source, ec);
         !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec))
      if (it->is_regular_file(ec)) files.push_back(it->path());
    std::sort(files.begin(), files.end());
    for (const auto& file : files) {
      struct stat s = {};
      if (::stat(file.c_str(), &s) == 0) {
        auto name = file.lexically_relative(source).string();
        hash = mix(hash, reinterpret_cast<const unsigned char*>(name.data()), name.size());
        add(file, s);
      }
    }
  }
  return {{"size", size}, {"mtime_ns", newest}, {"sampled_checksum", hex(hash)}};
}

} // namespace geotandem::volume
