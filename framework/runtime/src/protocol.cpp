// Encoding and checking of the runtime's messages (protocol.hpp).
#include "geotandem/runtime/protocol.hpp"

#include <xxhash.h>

#include <bit>

#include "byte_stream.hpp"

namespace geotandem::runtime {

static_assert(std::endian::native == std::endian::little, "the runtime's messages are little-endian");

namespace {

using detail::ByteReader;
using detail::ByteWriter;

constexpr char kMagic[4] = {'G', 'T', 'R', 'T'};

bool known(std::uint8_t k) {
  return (k >= 1 && k <= 10) || (k >= 16 && k <= 23);
}

void put_array(ByteWriter& w, const std::array<double, 3>& a) {
  for (double x : a)
    w.put(x);
}
std::array<double, 3> get_array(ByteReader& r) {
  std::array<double, 3> a{};
  for (double& x : a)
    x = r.get<double>();
  return a;
}

void put_entry(ByteWriter& w, const store::IndexEntry& e) {
  w.put(e.key);
  w.put_text(e.location.shard);
  w.put(e.location.offset);
  w.put(e.location.length);
  w.put(e.location.checksum);
  w.put(e.location.vertex_count);
  w.put(e.location.triangle_count);
  const mesh::ComponentStats& s = e.stats;
  w.put(s.vertex_count);
  w.put(s.triangle_count);
  w.put(static_cast<std::uint8_t>(s.closed));
  // Bits 0-5: the cut faces; bit 7: cut by the border.
  w.put(static_cast<std::uint8_t>(s.cut_faces | (s.cut_by_border ? 0x80u : 0u)));
  w.put(s.volume);
  w.put(s.area);
  put_array(w, s.centroid);
  put_array(w, s.box_min);
  put_array(w, s.box_max);
  put_array(w, s.obb_center);
  for (const auto& axis : s.obb_axes)
    put_array(w, axis);
  put_array(w, s.obb_half_extents);
  w.put(s.azimuth);
  w.put(s.dip);
  w.put(s.elongation);
  w.put(s.cap_area);
  w.put(static_cast<std::uint8_t>(e.run.has_value()));
  w.put(e.run.value_or(0));
  w.put(s.samples); // protocol 4
}

store::IndexEntry get_entry(ByteReader& r) {
  store::IndexEntry e;
  e.key = r.get<std::uint64_t>();
  e.location.shard = r.get_text("a shard name");
  e.location.offset = r.get<std::uint64_t>();
  e.location.length = r.get<std::uint64_t>();
  e.location.checksum = r.get<std::uint64_t>();
  e.location.vertex_count = r.get<std::uint64_t>();
  e.location.triangle_count = r.get<std::uint64_t>();
  mesh::ComponentStats& s = e.stats;
  s.vertex_count = r.get<std::uint64_t>();
  s.triangle_count = r.get<std::uint64_t>();
  s.closed = r.get<std::uint8_t>() != 0;
  const auto cut = r.get<std::uint8_t>();
  s.cut_by_border = cut != 0;
  s.cut_faces = static_cast<std::uint8_t>(cut & 0x3fu);
  s.volume = r.get<double>();
  s.area = r.get<double>();
  s.centroid = get_array(r);
  s.box_min = get_array(r);
  s.box_max = get_array(r);
  s.obb_center = get_array(r);
  for (auto& axis : s.obb_axes)
    axis = get_array(r);
  s.obb_half_extents = get_array(r);
  s.azimuth = r.get<double>();
  s.dip = r.get<double>();
  s.elongation = r.get<double>();
  s.cap_area = r.get<double>();
  const bool has_run = r.get<std::uint8_t>() != 0;
  const auto run = r.get<std::int64_t>();
  if (has_run) e.run = run;
  s.samples = r.get<std::int64_t>();
  return e;
}

// The smallest encoded entry: every fixed field and an empty shard name.
constexpr std::size_t kMinEntryBytes = 8 + 8 + 5 * 8 + 2 * 8 + 2 + 2 * 8 + 18 * 8 + 3 * 8 + 8 + 1 + 8 + 8;

} // namespace

const char* to_string(MessageKind kind) {
  switch (kind) {
  case MessageKind::hello: return "HELLO";
  case MessageKind::ask: return "ASK";
  case MessageKind::done: return "DONE";
  case MessageKind::surface: return "SURFACE";
  case MessageKind::commit: return "COMMIT";
  case MessageKind::failed: return "FAILED";
  case MessageKind::heartbeat: return "HEARTBEAT";
  case MessageKind::surface_chunk: return "SURFACE-CHUNK";
  case MessageKind::merge_credit: return "MERGE-CREDIT";
  case MessageKind::retire: return "RETIRE";
  case MessageKind::merge_chunk: return "MERGE-CHUNK";
  case MessageKind::surface_credit: return "SURFACE-CREDIT";
  case MessageKind::setup: return "SETUP";
  case MessageKind::extract: return "EXTRACT";
  case MessageKind::send: return "SEND";
  case MessageKind::merge: return "MERGE";
  case MessageKind::wait: return "WAIT";
  case MessageKind::finished: return "FINISHED";
  }
  return "?";
}

std::vector<std::byte> encode(const Message& m) {
  ByteWriter w;
  for (char c : kMagic)
    w.put(static_cast<std::uint8_t>(c));
  w.put(kProtocolVersion);
  w.put(static_cast<std::uint8_t>(m.kind));
  w.put(std::uint8_t{0});
  w.put(std::uint32_t{0}); // payload length, below
  w.put(std::uint32_t{0}); // checksum, below
  w.put(m.lease.task);
  w.put(m.lease.attempt);
  w.put(m.number);
  w.put_text(m.text);
  w.put_bytes(m.bytes);
  for (std::int64_t v : m.box)
    w.put(v);
  w.put(static_cast<std::uint64_t>(m.entries.size()));
  for (const store::IndexEntry& e : m.entries)
    put_entry(w, e);
  std::vector<std::byte>& out = w.bytes();
  const std::size_t length = out.size() - kHeaderSize;
  if (length > 0xffffffffu) throw ProtocolError("message: " + std::to_string(length) + " bytes, over 4 GiB");
  const auto length32 = static_cast<std::uint32_t>(length);
  const auto hash =
      static_cast<std::uint32_t>(XXH32(out.data() + kHeaderSize, length, static_cast<std::uint8_t>(m.kind)));
  std::memcpy(out.data() + 8, &length32, 4);
  std::memcpy(out.data() + 12, &hash, 4);
  return std::move(out);
}

Message decode(std::span<const std::byte> frame, std::size_t max_bytes) {
  if (frame.size() > max_bytes)
    throw ProtocolError("message of " + std::to_string(frame.size()) + " bytes, over the cap of " +
                        std::to_string(max_bytes));
  if (frame.size() < kHeaderSize)
    throw ProtocolError("message of " + std::to_string(frame.size()) + " bytes, shorter than its " +
                        std::to_string(kHeaderSize) + "-byte header (truncated)");
  if (std::memcmp(frame.data(), kMagic, sizeof(kMagic)) != 0)
    throw ProtocolError("message without the GTRT magic (not a geotandem runtime message)");
  ByteReader h(frame.subspan(4, kHeaderSize - 4));
  const auto version = h.get<std::uint16_t>();
  const auto kind = h.get<std::uint8_t>();
  const auto flags = h.get<std::uint8_t>();
  const auto length = h.get<std::uint32_t>();
  const auto hash = h.get<std::uint32_t>();
  if (version != kProtocolVersion)
    throw ProtocolError("message of protocol version " + std::to_string(version) + ", this build speaks " +
                            std::to_string(kProtocolVersion),
                        {}, "run the same geotandem version on the manager and every worker");
  if (!known(kind)) throw ProtocolError("message of unknown kind " + std::to_string(kind));
  if (flags != 0) throw ProtocolError("message with unknown flags " + std::to_string(flags));
  const std::span<const std::byte> payload = frame.subspan(kHeaderSize);
  if (length != payload.size())
    throw ProtocolError("message header announces " + std::to_string(length) + " payload bytes, " +
                        std::to_string(payload.size()) + " follow" + (length > payload.size() ? " (truncated)" : ""));
  if (static_cast<std::uint32_t>(XXH32(payload.data(), payload.size(), kind)) != hash)
    throw ProtocolError("message checksum mismatch (damaged in transit)");
  Message m;
  m.kind = static_cast<MessageKind>(kind);
  ByteReader r(payload);
  m.lease.task = r.get<std::uint64_t>();
  m.lease.attempt = r.get<std::uint32_t>();
  m.number = r.get<std::uint64_t>();
  m.text = r.get_text("a text field");
  const auto b = r.get_bytes("a surface record");
  m.bytes.assign(b.begin(), b.end());
  for (std::int64_t& v : m.box)
    v = r.get<std::int64_t>();
  const std::size_t n = r.count(kMinEntryBytes, "component entries");
  m.entries.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    m.entries.push_back(get_entry(r));
  if (!r.done()) throw ProtocolError("message with trailing bytes after its last field");
  return m;
}

} // namespace geotandem::runtime
