#include "geotandem/volume/size_guard.hpp"

#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "geotandem/core/error.hpp"

namespace geotandem::volume {

std::optional<std::uint64_t> checked_byte_count(const Index3& shape, std::uint64_t bytes_per_sample) {
  std::uint64_t total = bytes_per_sample;
  for (auto n : shape) {
    if (n < 0) return std::nullopt;
    if (__builtin_mul_overflow(total, static_cast<std::uint64_t>(n), &total)) return std::nullopt;
  }
  return total;
}

std::uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return 0;
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page);
}

std::optional<std::uint64_t> free_disk_bytes(const std::filesystem::path& path) {
  struct statvfs info = {};
  if (::statvfs(path.c_str(), &info) != 0) return std::nullopt;
  return static_cast<std::uint64_t>(info.f_bavail) * static_cast<std::uint64_t>(info.f_frsize);
}

std::string byte_size_text(std::uint64_t bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double value = static_cast<double>(bytes);
  int unit = 0;
  while (value >= 1024 && unit < 6) {
    value /= 1024;
    ++unit;
  }
  char text[64];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.1f %s", value, units[unit]);
  return text;
}

void check_shape_fits(const Index3& shape, const std::string& what) {
  const std::string dims =
      std::to_string(shape[0]) + " x " + std::to_string(shape[1]) + " x " + std::to_string(shape[2]);
  auto bytes = checked_byte_count(shape, sizeof(float));
  if (!bytes)
    throw InvalidArgument(what + " " + dims + " needs more than 2^64 bytes of float32 samples", {},
                          "use a smaller shape");
  Index3 sorted = shape;
  std::sort(sorted.begin(), sorted.end());
  auto slice = checked_byte_count({1, sorted[1], sorted[2]}, 2 * sizeof(float));
  const std::uint64_t memory = physical_memory_bytes();
  if (memory && (!slice || *slice > memory))
    throw InvalidArgument(what + " " + dims + " (" + byte_size_text(*bytes) + " of float32) needs at least " +
                              (slice ? byte_size_text(*slice) : std::string("more than 2^64 bytes")) +
                              " of memory for two slices, and this machine has " + byte_size_text(memory),
                          {}, "use a smaller shape");
}

void check_disk_fits(const Index3& shape, const std::filesystem::path& path, const std::string& what) {
  std::error_code ec;
  std::filesystem::path dir = std::filesystem::absolute(path, ec).parent_path();
  while (!dir.empty() && !std::filesystem::is_directory(dir, ec) && dir != dir.root_path())
    dir = dir.parent_path();
  const auto free = free_disk_bytes(dir);
  const auto bytes = checked_byte_count(shape, sizeof(float));
  if (!free || (bytes && *bytes <= *free)) return;
  throw IoError(what + " needs " + (bytes ? byte_size_text(*bytes) : std::string("more than 2^64 bytes")) +
                    " of float32 samples on disk, and " + dir.string() + " has " + byte_size_text(*free) + " free",
                {path.string()}, "free some space, write elsewhere, or use a smaller shape");
}

} // namespace geotandem::volume
