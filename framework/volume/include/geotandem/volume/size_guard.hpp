#pragma once
// Overflow-safe size arithmetic for cubes, and the machine's limits, so that an absurd shape is
// refused with the numbers instead of wrapping around ("needs 0 bytes") or running away.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "geotandem/volume/box.hpp"

namespace geotandem::volume {

// shape[0] * shape[1] * shape[2] * bytes_per_sample, or std::nullopt when a factor is negative or the
// product does not fit in 64 bits.
std::optional<std::uint64_t> checked_byte_count(const Index3& shape, std::uint64_t bytes_per_sample);

// The machine's physical memory in bytes (0 when unknown).
std::uint64_t physical_memory_bytes();
// Free bytes on the file system holding `path` (std::nullopt when unknown).
std::optional<std::uint64_t> free_disk_bytes(const std::filesystem::path& path);

// "4.0 GiB"
std::string byte_size_text(std::uint64_t bytes);

// Throws InvalidArgument naming `what`, with the numbers, when the float32 cube of `shape` overflows
// 64-bit byte counts, or when one slice of it across its largest two axes (the least an extraction
// holds in memory, twice over) exceeds the machine's physical memory.
void check_shape_fits(const Index3& shape, const std::string& what);

// Throws IoError naming `path` and `what`, with the numbers, when the float32 cube of `shape` does
// not fit in the free space of the file system that would hold `path` (the nearest existing
// directory above it). Nothing is thrown when the free space cannot be read.
void check_disk_fits(const Index3& shape, const std::filesystem::path& path, const std::string& what);

} // namespace geotandem::volume
