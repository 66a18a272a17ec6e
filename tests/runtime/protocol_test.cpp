// The runtime's messages without sockets: round trips of every kind, and garbage, truncated,
// damaged, oversized and random frames refused with ProtocolError, never a crash.
#include <gtest/gtest.h>

#include <xxhash.h>

#include <cstring>
#include <random>

#include "geotandem/runtime/manager.hpp"
#include "geotandem/runtime/protocol.hpp"
#include "geotandem/runtime/surface_chunks.hpp"

namespace geotandem::runtime {
namespace {

Message sample() {
  Message m;
  m.kind = MessageKind::commit;
  m.lease = {42, 3};
  m.number = 123456789;
  m.text = "worker-7f3a";
  m.bytes = {std::byte{1}, std::byte{2}, std::byte{255}};
  m.box = {0, 8, 16, 32, 40, 48};
  store::IndexEntry e;
  e.key = 987654321;
  e.location = {"w-1", 100, 2000, 0xdeadbeef, 30, 56};
  e.stats.vertex_count = 30;
  e.stats.triangle_count = 56;
  e.stats.closed = true;
  e.stats.volume = 12.5;
  e.stats.area = 33.25;
  e.stats.centroid = {1, 2, 3};
  e.stats.obb_axes[2] = {0, 0, 1};
  e.stats.azimuth = 45;
  e.run = 2;
  m.entries = {e, e};
  m.entries[1].key = 5;
  m.entries[1].run.reset();
  return m;
}

TEST(Protocol, EveryFieldSurvivesARoundTrip) {
  const Message m = sample();
  const Message d = decode(encode(m));
  EXPECT_EQ(d.kind, m.kind);
  EXPECT_EQ(d.lease, m.lease);
  EXPECT_EQ(d.number, m.number);
  EXPECT_EQ(d.text, m.text);
  EXPECT_EQ(d.bytes, m.bytes);
  EXPECT_EQ(d.box, m.box);
  ASSERT_EQ(d.entries.size(), 2u);
  EXPECT_EQ(d.entries[0].key, 987654321u);
  EXPECT_EQ(d.entries[0].location, m.entries[0].location);
  EXPECT_EQ(d.entries[0].stats.volume, 12.5);
  EXPECT_EQ(d.entries[0].stats.obb_axes[2], (std::array<double, 3>{0, 0, 1}));
  EXPECT_TRUE(d.entries[0].stats.closed);
  EXPECT_EQ(d.entries[0].run, std::optional<std::int64_t>(2));
  EXPECT_FALSE(d.entries[1].run.has_value());
  for (MessageKind k : {MessageKind::hello, MessageKind::ask, MessageKind::heartbeat, MessageKind::wait,
                        MessageKind::finished, MessageKind::merge, MessageKind::retire}) {
    Message x;
    x.kind = k;
    EXPECT_EQ(decode(encode(x)).kind, k) << to_string(k);
  }
}

void expect_refused(std::span<const std::byte> frame, const std::string& what, std::size_t cap = kDefaultMaxMessage) {
  try {
    decode(frame, cap);
    ADD_FAILURE() << "accepted: " << what;
  } catch (const ProtocolError& e) {
    EXPECT_FALSE(std::string(e.what()).empty());
  }
}

// RETIRE came with version 3: a version-2 peer's frame is refused by its version, and the kind
// after RETIRE is still unknown.
TEST(Protocol, RetireIsAVersion3KindWithItsReason) {
  Message r;
  r.kind = MessageKind::retire;
  r.text = "40 s left of its 600 s walltime";
  const Message d = decode(encode(r));
  EXPECT_EQ(d.kind, MessageKind::retire);
  EXPECT_EQ(d.text, r.text);
  EXPECT_STREQ(to_string(MessageKind::retire), "RETIRE");
  auto old = encode(r);
  old[4] = std::byte{2};
  expect_refused(old, "a version-2 RETIRE");
  Message next;
  next.kind = static_cast<MessageKind>(11);
  expect_refused(encode(next), "kind 11");
}

TEST(Protocol, DamagedFramesAreRefusedWithAReason) {
  const std::vector<std::byte> good = encode(sample());
  for (std::size_t n = 0; n < good.size(); ++n)
    expect_refused(std::span(good).first(n), "truncated to " + std::to_string(n));
  auto longer = good;
  longer.push_back(std::byte{0});
  expect_refused(longer, "a trailing byte");
  for (std::size_t i = 0; i < good.size(); ++i) {
    auto bad = good;
    bad[i] ^= std::byte{0x10};
    expect_refused(bad, "bit flip at " + std::to_string(i));
  }
  expect_refused(good, "over the cap", good.size() - 1);
  EXPECT_NO_THROW(decode(good, good.size()));
}

TEST(Protocol, AnotherVersionIsNamed) {
  auto bad = encode(sample());
  bad[4] = std::byte{9};
  try {
    decode(bad);
    FAIL();
  } catch (const ProtocolError& e) {
    EXPECT_NE(std::string(e.what()).find("version 9"), std::string::npos) << e.what();
  }
}

TEST(Protocol, RandomBytesNeverCrash) {
  std::mt19937 rng(11);
  const std::vector<std::byte> good = encode(sample());
  int accepted = 0;
  for (int i = 0; i < 20000; ++i) {
    std::vector<std::byte> frame;
    if (i % 2 == 0) {
      frame.resize(rng() % 200);
      for (auto& b : frame)
        b = static_cast<std::byte>(rng());
    } else { // a valid header with random payload bytes: reaches the field readers
      frame = good;
      for (int k = 0; k < 4; ++k)
        frame[kHeaderSize + rng() % (frame.size() - kHeaderSize)] = static_cast<std::byte>(rng());
    }
    try {
      decode(frame);
      ++accepted;
    } catch (const ProtocolError&) {
    }
  }
  EXPECT_EQ(accepted, 0) << "random payloads fail their checksum";
}

TEST(Protocol, ACorruptCountDoesNotAllocateWildly) {
  // A self-consistent frame (checksum recomputed) whose entry count claims 2^60 entries.
  Message m;
  m.kind = MessageKind::commit;
  auto frame = encode(m);
  const std::size_t count_at = frame.size() - 8;
  const std::uint64_t huge = std::uint64_t{1} << 60;
  std::memcpy(frame.data() + count_at, &huge, 8);
  const auto hash = static_cast<std::uint32_t>(
      XXH32(frame.data() + kHeaderSize, frame.size() - kHeaderSize, static_cast<std::uint8_t>(MessageKind::commit)));
  std::memcpy(frame.data() + 12, &hash, 4);
  try {
    decode(frame);
    FAIL() << "a count of 2^60 entries was accepted";
  } catch (const ProtocolError& e) {
    EXPECT_NE(std::string(e.what()).find("does not fit"), std::string::npos) << e.what();
  }
}

// The collapse counters a worker's last DONE carries: each by its name, distinct values so that a
// swapped pair shows; a key this build does not know (a newer worker) is ignored, a missing one is
// 0, and text that is not an object of counts is refused with what it was.
TEST(Protocol, CollapseCountersSurviveTheirTextAndBadTextIsRefused) {
  tandem::SimplifyCounters c;
  std::uint64_t value = 1000;
  for (auto field : tandem::SimplifyCounters::all)
    c.*field = value += 7;
  const tandem::SimplifyCounters back = counters_from_json(counters_to_json(c));
  for (std::size_t i = 0; i < tandem::SimplifyCounters::all.size(); ++i)
    EXPECT_EQ(back.*tandem::SimplifyCounters::all[i], c.*tandem::SimplifyCounters::all[i])
        << tandem::SimplifyCounters::names[i];
  const tandem::SimplifyCounters partial = counters_from_json(R"({"collapses": 5, "a_newer_counter": 9})");
  EXPECT_EQ(partial.collapses, 5u);
  EXPECT_EQ(partial.evaluations, 0u);
  for (const char* bad : {"", "[1, 2]", "{\"collapses\": -3}", "{\"collapses\": \"many\"}", "{\"collapses\": 1"}) {
    try {
      counters_from_json(bad);
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const ProtocolError& e) {
      EXPECT_NE(std::string(e.what()).find("collapse counter"), std::string::npos) << e.what();
    }
  }
}

// Chunks of a partial surface: in order they make the record back; out of order, replayed,
// oversized, past the cap, truncated or damaged they are refused with a reason, never a crash.
TEST(SurfaceChunks, AssembleInOrderAndRefuseEverythingElse) {
  std::vector<std::byte> record(10000);
  std::mt19937 rng(3);
  for (std::byte& b : record)
    b = static_cast<std::byte>(rng());
  const auto chunks = cut_into_chunks(record, 4096);
  ASSERT_EQ(chunks.size(), 3u);
  EXPECT_EQ(chunks[2].size(), 10000u - 8192u);
  const std::uint64_t sum = surface_checksum(record);
  {
    SurfaceAssembler in(1 << 20, std::nullopt, 4096);
    std::uint64_t at = 0;
    for (auto c : chunks) {
      EXPECT_FALSE(in.add(at, c));
      at += c.size();
    }
    EXPECT_FALSE(in.finish(record.size(), sum));
    EXPECT_EQ(in.take(), record);
  }
  {
    SurfaceAssembler in(1 << 20, record.size(), 4096); // announced (MERGE)
    EXPECT_FALSE(in.add(0, chunks[0]));
    EXPECT_FALSE(in.complete());
    const auto replayed = in.add(0, chunks[0]);
    ASSERT_TRUE(replayed);
    EXPECT_NE(replayed->find("out of order"), std::string::npos) << *replayed;
    EXPECT_TRUE(in.broken());
    EXPECT_TRUE(in.add(4096, chunks[1])) << "nothing is taken after a refusal";
    EXPECT_TRUE(in.finish(record.size(), sum));
  }
  {
    SurfaceAssembler in(1 << 20, std::nullopt, 4096);
    const auto big = in.add(0, std::span(record).first(5000));
    ASSERT_TRUE(big);
    EXPECT_NE(big->find("5000 bytes"), std::string::npos) << *big;
  }
  {
    SurfaceAssembler in(6000, std::nullopt, 4096); // the cap
    EXPECT_FALSE(in.add(0, chunks[0]));
    const auto over = in.add(4096, chunks[1]);
    ASSERT_TRUE(over);
    EXPECT_NE(over->find("cap"), std::string::npos) << *over;
  }
  {
    SurfaceAssembler in(1 << 20, std::nullopt, 4096); // truncated: the last chunk never came
    EXPECT_FALSE(in.add(0, chunks[0]));
    EXPECT_FALSE(in.add(4096, chunks[1]));
    const auto cut = in.finish(record.size(), sum);
    ASSERT_TRUE(cut);
    EXPECT_NE(cut->find("truncated"), std::string::npos) << *cut;
  }
  {
    SurfaceAssembler in(1 << 20, std::nullopt, 4096); // one flipped byte
    std::vector<std::byte> damaged(chunks[1].begin(), chunks[1].end());
    damaged[100] ^= std::byte{0x20};
    EXPECT_FALSE(in.add(0, chunks[0]));
    EXPECT_FALSE(in.add(4096, damaged));
    EXPECT_FALSE(in.add(8192, chunks[2]));
    const auto bad = in.finish(record.size(), sum);
    ASSERT_TRUE(bad);
    EXPECT_NE(bad->find("checksum"), std::string::npos) << *bad;
  }
  {
    SurfaceAssembler in(1 << 20, 5000000, 4096); // an announced total over the cap
    EXPECT_TRUE(in.broken());
    EXPECT_TRUE(in.add(0, chunks[0]));
  }
  { // a SEND's size hint: room for the record at once; a wrong hint changes no outcome
    SurfaceAssembler in(1 << 20, std::nullopt, 4096);
    in.reserve_hint(record.size());
    EXPECT_GE(in.capacity(), record.size());
    std::uint64_t at = 0;
    for (auto c : chunks) {
      EXPECT_FALSE(in.add(at, c));
      at += c.size();
    }
    // One allocation of the record's size (libstdc++ reserves exactly; grown chunk by chunk it
    // would hold 16384 bytes).
    EXPECT_EQ(in.capacity(), record.size()) << "the hint's room was not the room used";
    EXPECT_FALSE(in.finish(record.size(), sum));
    EXPECT_EQ(in.take(), record);
  }
  for (std::uint64_t hint : {std::uint64_t{100}, std::uint64_t{50000}, std::uint64_t{1} << 40}) {
    SurfaceAssembler in(1 << 20, std::nullopt, 4096);
    in.reserve_hint(hint);
    EXPECT_LE(in.capacity(), std::uint64_t{1} << 20) << "a hint over the cap reserved room";
    std::uint64_t at = 0;
    for (auto c : chunks) {
      EXPECT_FALSE(in.add(at, c)) << "hint " << hint;
      at += c.size();
    }
    EXPECT_FALSE(in.finish(record.size(), sum)) << "hint " << hint;
    EXPECT_EQ(in.take(), record);
  }
  {
    SurfaceAssembler in(1 << 20, std::nullopt, 4096); // random chunks never crash
    for (int i = 0; i < 200; ++i) {
      std::vector<std::byte> piece(rng() % 6000);
      (void)in.add(rng() % 20000, piece);
    }
    EXPECT_TRUE(in.finish(rng() % 20000, rng()));
  }
}

} // namespace
} // namespace geotandem::runtime
