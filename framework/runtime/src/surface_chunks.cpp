// Partial surfaces in chunks (surface_chunks.hpp).
#include "geotandem/runtime/surface_chunks.hpp"

#include <xxhash.h>

#include <algorithm>
#include <exception>

namespace geotandem::runtime {

std::uint64_t surface_checksum(std::span<const std::byte> record) {
  return XXH64(record.data(), record.size(), 0);
}

std::vector<std::span<const std::byte>> cut_into_chunks(std::span<const std::byte> record, std::size_t chunk_bytes) {
  std::vector<std::span<const std::byte>> out;
  for (std::size_t at = 0; at < record.size(); at += chunk_bytes)
    out.push_back(record.subspan(at, std::min(chunk_bytes, record.size() - at)));
  return out;
}

SurfaceAssembler::SurfaceAssembler(std::uint64_t max_total, std::optional<std::uint64_t> announced,
                                   std::size_t chunk_bytes)
    : max_total_(max_total), announced_(announced), chunk_bytes_(chunk_bytes) {
  if (announced_ && *announced_ > max_total_) broken_ = true;
  // Room for the whole record at once when its size is announced: grown chunk by chunk, it would
  // be copied at every doubling, into pages faulted in anew each time.
  if (announced_ && !broken_) bytes_.reserve(*announced_);
}

void SurfaceAssembler::reserve_hint(std::uint64_t bytes) {
  if (broken_ || bytes == 0 || bytes > max_total_) return;
  try {
    bytes_.reserve(static_cast<std::size_t>(bytes));
  } catch (const std::exception&) {
    // No room at once: the record grows chunk by chunk, as without the hint.
  }
}

std::optional<std::string> SurfaceAssembler::add(std::uint64_t offset, std::span<const std::byte> piece) {
  auto refuse = [&](std::string why) {
    broken_ = true;
    return std::optional<std::string>(std::move(why));
  };
  if (broken_) return "a chunk of a surface already refused";
  if (announced_ && *announced_ > max_total_)
    return refuse("a surface of " + std::to_string(*announced_) + " bytes, over the cap of " +
                  std::to_string(max_total_));
  if (piece.empty() || piece.size() > chunk_bytes_)
    return refuse("a chunk of " + std::to_string(piece.size()) + " bytes (1 to " + std::to_string(chunk_bytes_) +
                  " expected)");
  if (offset != bytes_.size())
    return refuse("a chunk at offset " + std::to_string(offset) + ", expected " + std::to_string(bytes_.size()) +
                  " (out of order, replayed or a chunk lost)");
  const std::uint64_t end = bytes_.size() + piece.size();
  if (end > max_total_) return refuse("a surface growing past the cap of " + std::to_string(max_total_) + " bytes");
  if (announced_ && end > *announced_)
    return refuse("a chunk past the announced " + std::to_string(*announced_) + " bytes");
  bytes_.insert(bytes_.end(), piece.begin(), piece.end());
  return std::nullopt;
}

std::optional<std::string> SurfaceAssembler::finish(std::uint64_t total, std::uint64_t checksum) {
  if (broken_) return "a surface with a refused chunk";
  if (total > max_total_) return "a surface of " + std::to_string(total) + " bytes, over the cap";
  if (bytes_.size() != total)
    return "a surface of " + std::to_string(total) + " bytes announced, " + std::to_string(bytes_.size()) +
           " received (truncated)";
  if (surface_checksum(bytes_) != checksum) return "a surface whose checksum does not match (damaged in transit)";
  return std::nullopt;
}

} // namespace geotandem::runtime
