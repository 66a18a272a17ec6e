#pragma once
// A partial surface in chunks (protocol.hpp): the sender cuts the record into pieces of at most
// kChunkBytes and announces its total size and XXH64 at the end (or, for a MERGE, at the start);
// the receiver appends the pieces in order and checks the size cap, the offsets, the total and the
// checksum. A piece that does not fit (oversized, out of order, past the cap or the announced
// total) is refused with the reason and leaves the assembly broken: the caller logs it, drops it,
// and treats the transfer as lost. Testable without sockets.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "geotandem/runtime/protocol.hpp"

namespace geotandem::runtime {

std::uint64_t surface_checksum(std::span<const std::byte> record);
// The chunks of a record, in order: [offset, offset + size).
std::vector<std::span<const std::byte>> cut_into_chunks(std::span<const std::byte> record,
                                                        std::size_t chunk_bytes = kChunkBytes);

class SurfaceAssembler {
public:
  // `max_total`: the size cap; `announced`: the total when known before the chunks (MERGE).
  explicit SurfaceAssembler(std::uint64_t max_total = kDefaultMaxSurface,
                            std::optional<std::uint64_t> announced = std::nullopt,
                            std::size_t chunk_bytes = kChunkBytes);

  // Room for `bytes` (at most the cap) before the chunks arrive: the size a SEND's sender states on
  // its first chunk. Only a hint: add() and finish() check as without it, and without room to
  // spare the record grows as it arrives.
  void reserve_hint(std::uint64_t bytes);
  // Appends the piece at `offset`; the reason it is refused otherwise (then broken() holds).
  std::optional<std::string> add(std::uint64_t offset, std::span<const std::byte> piece);
  // True once the announced total has arrived.
  bool complete() const { return announced_ && bytes_.size() == *announced_; }
  // Checks the total and the checksum; the record, or the reason it is refused.
  std::optional<std::string> finish(std::uint64_t total, std::uint64_t checksum);
  std::vector<std::byte> take() { return std::move(bytes_); }

  bool broken() const { return broken_; }
  std::uint64_t size() const { return bytes_.size(); }
  std::uint64_t capacity() const { return bytes_.capacity(); } // the room held

private:
  std::uint64_t max_total_;
  std::optional<std::uint64_t> announced_;
  std::size_t chunk_bytes_;
  std::vector<std::byte> bytes_;
  bool broken_ = false;
};

} // namespace geotandem::runtime
