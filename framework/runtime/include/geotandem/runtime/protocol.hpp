#pragma once
// The messages between the manager and its workers, and their wire form, testable without
// sockets. One message is one ZeroMQ frame (the manager's ROUTER adds the worker's routing id in
// front):
//   header, 16 bytes: magic "GTRT", protocol version (u16), kind (u8), flags (u8, none defined),
//                     payload length (u32), XXH32 of the payload seeded with the kind
//                     (u32, so a damaged kind is caught too); little-endian
//   payload: the kind's fields in a fixed order (strings and byte blocks with a u64 length).
// decode() refuses a message of another version, an unknown kind, a length that disagrees with the
// frame, a failed checksum, a field that runs past the payload, trailing bytes, and anything over
// the size cap: it throws ProtocolError, which the transport logs before dropping the message.
//
// Leases: every task carries (task, attempt); a worker's result repeats it, and the manager
// ignores a result whose lease is not the one it gave that worker last (a late or replayed result
// of an old attempt).
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/store/store.hpp"

namespace geotandem::runtime {

// 3: RETIRE (a worker near its walltime hands back its surface). 4: SETUP carries the extraction
// options as one object in their own codec (tandem::to_json), block_size 0 included.
// 5: COMMIT entries end with the samples each component encloses (issue 54). 6: an EXTRACT's bytes
// name the finished leaves of its batch, which the worker skips, and its DONE's bytes the merges
// inside the batch (issue 55).
inline constexpr std::uint16_t kProtocolVersion = 6;
inline constexpr std::size_t kHeaderSize = 16;
// Largest message either side accepts. Also set as ZMQ_MAXMSGSIZE on both sockets.
inline constexpr std::size_t kDefaultMaxMessage = std::size_t{1} << 30;
// Partial surfaces travel in chunks of at most this many bytes, at most kChunkWindow chunks ahead
// of the receiver's credits; a whole surface is at most kDefaultMaxSurface bytes.
inline constexpr std::size_t kChunkBytes = std::size_t{1} << 20;
inline constexpr std::size_t kChunkWindow = 8;
inline constexpr std::uint64_t kDefaultMaxSurface = std::uint64_t{1} << 34;

enum class MessageKind : std::uint8_t {
  // worker -> manager
  hello = 1,         // token, pid: the worker is up
  ask = 2,           // the seed's get_task()
  done = 3,          // lease, number = the task's CPU microseconds (the worker process's user + system; the
                     // scale model's demand), box[0] = peak RSS (KiB), box[1] bit 0: the worker's
                     // surface is empty after it (it dropped it), bit 1: the EXTRACT's leaves left
                     // nothing open by themselves; after the final FINISHED,
                     // box[2], box[3] = marching-cubes triangles and collapses of the whole surface;
                     // box[5] = the task's microseconds (0 from an older worker; for the task log); bytes
                     // (EXTRACT): the merges inside its batch (batch_extract.hpp)
  surface = 4,       // lease, number = total bytes, box[0] = XXH64 of them: the end of the worker's surface for
                     // its SEND (sent before as surface_chunk; relayed by the manager)
  commit = 5,        // lease, entries: components written (and synced) to the worker's shard
  failed = 6,        // lease, text: the task failed; the worker goes on
  heartbeat = 7,     // both ways
  surface_chunk = 8, // lease, number = offset, bytes: a piece of the surface of a SEND
  merge_credit = 9,  // lease, number = chunks of a MERGE consumed: the manager may send that many more
  retire = 10,       // text = why: like ASK, from a worker near its walltime; it takes no EXTRACT any more,
                     // hands its surface to another worker (SEND) and is then told FINISHED
  // manager -> worker
  setup = 16,          // text: the run's description (JSON: volume, options, store, shard)
  extract = 17,        // lease, number = node id, box = its cells, bytes = the finished leaves of the batch to
                       // skip: (first, count) u32 pairs of leaf ordinals in tree order (batch_extract.hpp)
  send = 18,           // lease, target: hand your surface over (to the manager, for that worker)
  merge = 19,          // lease, number = total bytes, box[0] = XXH64: merge this surface (as merge_chunk) into yours
  wait = 20,           // number: milliseconds before asking again
  finished = 21,       // lease, number: 1 = finish and dump the whole surface, then stop; 0 = stop
  merge_chunk = 22,    // lease, number = offset, bytes: a piece of the surface of a MERGE
  surface_credit = 23, // lease, number = chunks of a SEND received: the worker may send that many more
};
const char* to_string(MessageKind kind);

struct Lease {
  std::uint64_t task = 0;
  std::uint32_t attempt = 0;
  bool operator==(const Lease&) const = default;
};

struct Message {
  MessageKind kind = MessageKind::heartbeat;
  Lease lease;
  std::uint64_t number = 0;               // pid, leaf node id, target, wait ms, final flag, seconds (ms)
  std::string text;                       // token, setup JSON, failure message
  std::vector<std::byte> bytes;           // a working-surface record
  std::array<std::int64_t, 6> box{};      // extract: the leaf's cells (lo, hi)
  std::vector<store::IndexEntry> entries; // commit
};

class ProtocolError : public DataError {
public:
  using DataError::DataError;
};

std::vector<std::byte> encode(const Message& message);
// Throws ProtocolError (see above). `max_bytes` caps the whole frame.
Message decode(std::span<const std::byte> frame, std::size_t max_bytes = kDefaultMaxMessage);

} // namespace geotandem::runtime
