// The manager's relay of partial surfaces (surface_relay.hpp).
#include "surface_relay.hpp"

#include <algorithm>

namespace geotandem::runtime::detail {

void SurfaceRelay::begin_inbound(const std::string& token) {
  inbound_.insert_or_assign(token, SurfaceAssembler(max_surface_, std::nullopt, chunk_bytes_));
}

std::optional<std::string> SurfaceRelay::chunk_in(const std::string& token, std::uint64_t offset,
                                                  std::span<const std::byte> bytes, std::uint64_t size_hint) {
  auto it = inbound_.find(token);
  if (it == inbound_.end()) return "a chunk outside a SEND";
  if (offset == 0) it->second.reserve_hint(size_hint);
  return it->second.add(offset, bytes);
}

std::optional<std::string> SurfaceRelay::end_inbound(const std::string& token, std::uint64_t total,
                                                     std::uint64_t checksum, std::uint64_t& bytes) {
  auto it = inbound_.find(token);
  if (it == inbound_.end()) return "the end of a SEND that did not start";
  SurfaceAssembler in = std::move(it->second);
  inbound_.erase(it);
  bytes = in.size();
  if (std::optional<std::string> why = in.finish(total, checksum)) return why;
  whole_.insert_or_assign(token, Parcel{in.take(), checksum});
  return std::nullopt;
}

void SurfaceRelay::keep(const std::string& token, TransferId transfer) {
  auto it = whole_.find(token);
  if (it == whole_.end()) return;
  kept_[transfer] = std::move(it->second);
  whole_.erase(it);
}

SurfaceRelay::Header SurfaceRelay::begin_outbound(const std::string& token, TransferId transfer) {
  Outbound out;
  out.parcel = std::move(kept_.at(transfer));
  kept_.erase(transfer);
  const Header h{out.parcel.bytes.size(), out.parcel.checksum};
  outbound_.insert_or_assign(token, std::move(out));
  return h;
}

void SurfaceRelay::pump(const std::string& token, std::uint64_t credits,
                        const std::function<void(std::uint64_t, std::span<const std::byte>)>& send) {
  auto it = outbound_.find(token);
  if (it == outbound_.end()) return;
  Outbound& out = it->second;
  out.ahead -= std::min(out.ahead, credits);
  const std::span<const std::byte> all(out.parcel.bytes);
  while (out.ahead < kChunkWindow && out.offset < all.size()) {
    const std::size_t n = std::min<std::size_t>(chunk_bytes_, all.size() - out.offset);
    send(out.offset, all.subspan(out.offset, n));
    out.offset += n;
    ++out.ahead;
  }
  if (out.offset >= all.size()) outbound_.erase(it); // every chunk is on its way
}

void SurfaceRelay::forget(const std::string& token) {
  inbound_.erase(token);
  outbound_.erase(token);
  whole_.erase(token);
}

void SurfaceRelay::drop_kept(const std::function<bool(TransferId)>& gone) {
  std::erase_if(kept_, [&](const auto& kv) { return gone(kv.first); });
}

} // namespace geotandem::runtime::detail
