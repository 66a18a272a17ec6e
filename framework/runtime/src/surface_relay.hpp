#pragma once
// The partial surfaces the manager relays (the route through the manager, protocol.hpp): each SEND
// arrives in chunks that are acknowledged with credits and assembled under a size cap, checked at
// its end (total and checksum), and kept until the target worker's MERGE; the MERGE goes out in
// chunks, at most kChunkWindow ahead of that worker's credits. No sockets here: the manager sends
// what this object returns. Internal to the runtime.
//
// The surfaces waiting for their MERGE are held in memory up to a budget; past it they wait in
// files of a spill directory (one file each, read back and removed when their MERGE starts), so
// a worker that merges more slowly than the others send cannot make the manager's memory grow
// without bound. A file that cannot be written leaves its surface in memory, with a warning.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "geotandem/runtime/schedule.hpp"
#include "geotandem/runtime/surface_chunks.hpp"

namespace geotandem::runtime::detail {

class SurfaceRelay {
public:
  // `memory`: the bytes of waiting surfaces held in memory at most; `spill_dir` (empty: never
  // spill) is created when first needed; the files a relay leaves behind (a manager killed) are
  // removed when the next relay on that directory starts.
  SurfaceRelay(std::uint64_t max_surface, std::size_t chunk_bytes, std::uint64_t memory = UINT64_MAX,
               std::filesystem::path spill_dir = {});
  ~SurfaceRelay();
  SurfaceRelay(const SurfaceRelay&) = delete;
  SurfaceRelay& operator=(const SurfaceRelay&) = delete;

  // A worker starts its SEND.
  void begin_inbound(const std::string& token);
  // A chunk of it: nullopt when taken (acknowledge it with a credit), the reason otherwise. The
  // first chunk's `size_hint` (the record's size as its sender states it, 0 for none) reserves
  // the room for the whole record at once.
  std::optional<std::string> chunk_in(const std::string& token, std::uint64_t offset, std::span<const std::byte> bytes,
                                      std::uint64_t size_hint = 0);
  // Its end: the reason it is refused, or nullopt when the surface is whole; `bytes` receives its
  // size. A whole surface is then kept for its transfer (keep) or dropped (its target died).
  std::optional<std::string> end_inbound(const std::string& token, std::uint64_t total, std::uint64_t checksum,
                                         std::uint64_t& bytes);
  // Returns a warning when the surface should have gone to disk and could not (it stays in memory).
  std::optional<std::string> keep(const std::string& token, TransferId transfer);

  struct Header {
    std::uint64_t total = 0;
    std::uint64_t checksum = 0;
  };
  // The MERGE of `transfer` to `token` starts: its header; the chunks follow through pump(). A
  // surface whose file is missing or damaged is an IoError naming the file.
  Header begin_outbound(const std::string& token, TransferId transfer);
  // `credits` chunks were consumed by the worker (0 at the start): calls `send(offset, piece)` for
  // each chunk it may send now.
  void pump(const std::string& token, std::uint64_t credits,
            const std::function<void(std::uint64_t, std::span<const std::byte>)>& send);

  // The worker is gone: its transfers in and out are dropped.
  void forget(const std::string& token);
  // Drops the kept surfaces for which `gone(transfer)` holds.
  void drop_kept(const std::function<bool(TransferId)>& gone);
  // The run is over: every surface is dropped and the spill directory removed (also on destruction).
  void close() noexcept;

  struct Usage {
    std::uint64_t held = 0, peak_held = 0;        // bytes of waiting surfaces in memory, now and at most
    std::uint64_t spilled = 0, spilled_bytes = 0; // surfaces that waited on disk
  };
  const Usage& usage() const { return usage_; }
  const std::filesystem::path& spill_dir() const { return spill_dir_; }

private:
  struct Parcel {
    std::vector<std::byte> bytes;
    std::uint64_t checksum = 0;
    std::uint64_t size = 0;     // of the surface, in memory or on disk
    std::filesystem::path file; // non-empty: the surface waits there
  };
  std::optional<std::string> spill(TransferId transfer, Parcel& parcel);
  void load(Parcel& parcel) const;
  // A kept surface leaves the relay's account: its memory is no longer counted, its file goes.
  void release(Parcel& parcel);
  struct Outbound {
    Parcel parcel;
    std::uint64_t offset = 0;
    std::uint64_t ahead = 0;
  };
  std::uint64_t max_surface_;
  std::size_t chunk_bytes_;
  std::map<std::string, SurfaceAssembler> inbound_;
  std::map<std::string, Outbound> outbound_;
  std::map<std::string, Parcel> whole_; // ended, not yet kept
  std::map<TransferId, Parcel> kept_;
  std::uint64_t memory_;
  std::filesystem::path spill_dir_;
  bool spill_failed_ = false; // warned once; later surfaces stay in memory
  Usage usage_;
};

} // namespace geotandem::runtime::detail
