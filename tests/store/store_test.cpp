// The store's core contract: round trips, one row per key, runs, selections, errors.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "fixtures.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/mesh/measure.hpp"
#include "geotandem/store/local_sink.hpp"
#include "geotandem/store/store.hpp"
#include "scratch.hpp"

namespace geotandem::store {
namespace {

using geotandem::testing::ScratchDir;
using testing::make_component;
using testing::same_stats;
using testing::same_surface;
using testing::test_geometry;

std::filesystem::path make_store(const ScratchDir& scratch, std::uint64_t count, std::size_t batch = 4,
                                 const std::string& name = "store") {
  auto dir = scratch.path() / name;
  auto store = ComponentStore::create(dir, test_geometry(), {"test store", "store_test"});
  LocalSink sink(store, {"local", std::nullopt, batch});
  for (std::uint64_t key = 1; key <= count; ++key)
    sink.commit(make_component(key * 3, test_geometry(), 2));
  sink.close();
  return dir;
}

void flip_byte(const std::filesystem::path& path, std::uint64_t offset) {
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  file.seekg(static_cast<std::streamoff>(offset));
  char byte = 0;
  file.read(&byte, 1);
  byte = static_cast<char>(byte ^ 0x10);
  file.seekp(static_cast<std::streamoff>(offset));
  file.write(&byte, 1);
  ASSERT_TRUE(file.good());
}

template <class E, class F> std::string message_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an exception";
  return {};
}

TEST(Store, RoundTripKeepsSurfaceInWorldCoordinatesAndStats) {
  ScratchDir scratch;
  auto dir = make_store(scratch, 20);
  auto store = ComponentStore::open(dir);
  EXPECT_EQ(store.geometry(), test_geometry());
  ASSERT_EQ(store.size(), 20u);
  for (std::uint64_t key = 3; key <= 60; key += 3) {
    auto component = make_component(key, test_geometry(), 2);
    auto row = store.find(key);
    ASSERT_TRUE(row) << key;
    EXPECT_TRUE(same_stats(row->stats, component.stats)) << key;
    EXPECT_EQ(row->location.shard, "local");
    auto world = store.read(key);
    EXPECT_TRUE(same_surface(world, mesh::to_world(component.surface, test_geometry()))) << key;
    EXPECT_NE(world.points.front(), component.surface.points.front()); // really world, not index, coordinates
  }
  EXPECT_FALSE(store.find(4));
  EXPECT_FALSE(store.contains(4));
}

TEST(Store, RecordsTileTheShardWithoutGaps) {
  ScratchDir scratch;
  auto dir = make_store(scratch, 15, 1);
  auto store = ComponentStore::open(dir);
  auto rows = store.query();
  std::sort(rows.begin(), rows.end(), [](auto& a, auto& b) { return a.location.offset < b.location.offset; });
  std::uint64_t end = 0;
  for (const auto& row : rows) {
    EXPECT_EQ(row.location.offset, end);
    EXPECT_EQ(row.location.length, 48 + 24 * row.location.vertex_count + 12 * row.location.triangle_count);
    end += row.location.length;
  }
  EXPECT_EQ(std::filesystem::file_size(shard_path(dir, "local")), end);
  EXPECT_EQ(store.indexed_end("local"), end);
}

TEST(Store, ComponentCommittedTwiceIsStoredOnce) {
  ScratchDir scratch;
  auto dir = scratch.path() / "store";
  auto store = ComponentStore::create(dir, test_geometry());
  {
    LocalSink sink(store, {"local", std::nullopt, 8});
    sink.commit(make_component(7, test_geometry()));
    sink.commit(make_component(7, test_geometry())); // pending twice
    sink.flush();
    sink.commit(make_component(7, test_geometry())); // already indexed
    sink.close();
    EXPECT_EQ(sink.committed(), 1u);
    EXPECT_EQ(sink.duplicates(), 2u);
  }
  const auto shard_size = std::filesystem::file_size(shard_path(dir, "local"));
  {
    LocalSink again(store, {"local", std::nullopt, 1});
    again.commit(make_component(7, test_geometry()));
    again.close();
  }
  EXPECT_EQ(std::filesystem::file_size(shard_path(dir, "local")), shard_size);
  // A manager committing the same key from two workers' shards keeps the first row.
  ShardWriter a(dir, "worker-a", test_geometry()), b(dir, "worker-b", test_geometry());
  auto c = make_component(11, test_geometry());
  auto la = a.append(c), lb = b.append(c);
  a.sync();
  b.sync();
  EXPECT_EQ(store.commit(IndexEntry{11, la, c.stats, std::nullopt}), 1u);
  EXPECT_EQ(store.commit(IndexEntry{11, lb, c.stats, std::nullopt}), 0u);
  EXPECT_EQ(store.find(11)->location.shard, "worker-a");
  EXPECT_EQ(store.size(), 2u);
  auto rows = store.query();
  std::set<std::uint64_t> keys;
  for (auto& r : rows)
    EXPECT_TRUE(keys.insert(r.key).second);
}

TEST(Store, WorkersWriteShardsAndTheManagerIndexes) {
  ScratchDir scratch;
  auto dir = scratch.path() / "store";
  auto store = ComponentStore::create(dir, test_geometry());
  ShardWriter w1(dir, "w1", store.geometry()), w2(dir, "w2", store.geometry());
  std::vector<IndexEntry> entries;
  for (std::uint64_t key = 1; key <= 10; ++key) {
    auto c = make_component(key, store.geometry());
    auto& writer = key % 2 ? w1 : w2;
    entries.push_back({key, writer.append(c), c.stats, std::nullopt});
  }
  w1.sync();
  w2.sync();
  EXPECT_EQ(store.commit(entries), 10u);
  for (std::uint64_t key = 1; key <= 10; ++key) {
    EXPECT_EQ(store.find(key)->location.shard, key % 2 ? "w1" : "w2");
    EXPECT_TRUE(
        same_surface(store.read(key), mesh::to_world(make_component(key, store.geometry()).surface, store.geometry())));
  }
  // The free function reads a record given its location, as a worker or tool would.
  auto row = *store.find(4);
  EXPECT_TRUE(same_surface(read_record(shard_path(dir, "w2"), row.location, 4), store.read(4)));
  EXPECT_THROW(read_record(shard_path(dir, "w2"), row.location, 5), FormatError);
}

TEST(Store, KeysAboveTwoToTheSixtyThreeRoundTrip) {
  ScratchDir scratch;
  auto store = ComponentStore::create(scratch.path() / "s", test_geometry());
  LocalSink sink(store, {"local", std::nullopt, 1});
  const std::uint64_t big = 0xfedcba9876543210ull;
  sink.commit(make_component(big, test_geometry()));
  sink.close();
  ASSERT_TRUE(store.contains(big));
  EXPECT_EQ(store.query().at(0).key, big);
  EXPECT_EQ(store.read(big).points.size(), make_component(big, test_geometry()).surface.points.size());
}

TEST(Store, FlippedByteIsDetectedAndNamesKeyShardAndOffset) {
  ScratchDir scratch;
  auto dir = make_store(scratch, 6, 1);
  auto store = ComponentStore::open(dir);
  auto victim = *store.find(9);
  flip_byte(shard_path(dir, "local"), victim.location.offset + victim.location.length / 2);
  auto reopened = ComponentStore::open(dir);
  auto message = message_of<FormatError>([&] { reopened.read(9); });
  EXPECT_NE(message.find("component 9"), std::string::npos) << message;
  EXPECT_NE(message.find("offset " + std::to_string(victim.location.offset)), std::string::npos) << message;
  EXPECT_NE(message.find("local.gts"), std::string::npos) << message;
  EXPECT_NE(message.find("checksum"), std::string::npos) << message;
  for (std::uint64_t key : {3, 6, 12, 15, 18})
    EXPECT_NO_THROW(reopened.read(key)) << key;
}

TEST(Store, ScanningWriterDropsATornTailAndAppendsAfterIt) {
  ScratchDir scratch;
  auto dir = scratch.path() / "store";
  auto store = ComponentStore::create(dir, test_geometry());
  std::vector<IndexEntry> entries;
  std::uint64_t valid_end = 0;
  {
    ShardWriter writer(dir, "w", test_geometry());
    for (std::uint64_t key = 1; key <= 3; ++key) {
      auto c = make_component(key, test_geometry());
      entries.push_back({key, writer.append(c), c.stats, std::nullopt});
    }
    writer.sync();
    valid_end = writer.end();
    // A fourth record cut in the middle, as a kill during the write leaves it.
    auto half = writer.append(make_component(4, test_geometry()));
    std::filesystem::resize_file(writer.path(), half.offset + half.length / 2);
  }
  store.commit(entries);
  std::uint64_t damaged_offset = 0;
  {
    ShardWriter reopened(dir, "w", test_geometry());
    EXPECT_EQ(reopened.end(), valid_end);
    EXPECT_GT(reopened.dropped_bytes(), 0u);
    EXPECT_EQ(std::filesystem::file_size(reopened.path()), valid_end);
    auto c = make_component(5, test_geometry());
    auto location = reopened.append(c);
    reopened.sync();
    EXPECT_EQ(location.offset, valid_end);
    store.commit(IndexEntry{5, location, c.stats, std::nullopt});
    // A complete record with a damaged byte also ends the valid part.
    auto damaged = reopened.append(make_component(6, test_geometry()));
    reopened.sync();
    damaged_offset = damaged.offset;
    flip_byte(reopened.path(), damaged.offset + 60);
  }
  ShardWriter again(dir, "w", test_geometry());
  EXPECT_EQ(again.end(), damaged_offset);
  for (std::uint64_t key : {1, 2, 3, 5})
    EXPECT_NO_THROW(store.read(key));
}

TEST(Store, LocalSinkCutsItsShardBackToTheIndexedEnd) {
  ScratchDir scratch;
  auto dir = make_store(scratch, 4, 1);
  auto indexed = std::filesystem::file_size(shard_path(dir, "local"));
  {
    // A record appended and never indexed, then garbage: a killed run's leftovers.
    auto store = ComponentStore::open(dir, OpenMode::read_write);
    ShardWriter writer(dir, "local", test_geometry(), {store.indexed_end("local")});
    writer.append(make_component(1000, test_geometry()));
    writer.sync();
    std::ofstream(shard_path(dir, "local"), std::ios::app | std::ios::binary) << "garbage";
  }
  EXPECT_GT(std::filesystem::file_size(shard_path(dir, "local")), indexed);
  auto store = ComponentStore::open(dir, OpenMode::read_write);
  LocalSink sink(store, {"local", std::nullopt, 1});
  EXPECT_EQ(std::filesystem::file_size(shard_path(dir, "local")), indexed);
  sink.commit(make_component(1000, test_geometry()));
  sink.close();
  EXPECT_EQ(store.find(1000)->location.offset, indexed);
  EXPECT_TRUE(
      same_surface(store.read(1000), mesh::to_world(make_component(1000, test_geometry()).surface, test_geometry())));
}

TEST(Store, SecondWriterOfTheSameShardIsRefused) {
  ScratchDir scratch;
  auto store = ComponentStore::create(scratch.path() / "s", test_geometry());
  ShardWriter first(store.directory(), "w", test_geometry());
  auto message = message_of<IoError>([&] { ShardWriter second(store.directory(), "w", test_geometry()); });
  EXPECT_NE(message.find("locked"), std::string::npos) << message;
  EXPECT_THROW(ShardWriter(store.directory(), "../escape", test_geometry()), InvalidArgument);
  EXPECT_THROW(ShardWriter(store.directory(), ".hidden", test_geometry()), InvalidArgument);
  EXPECT_THROW(ShardWriter(store.directory(), "", test_geometry()), InvalidArgument);
  // An index that knows more bytes than the shard holds means lost records.
  EXPECT_THROW(ShardWriter(store.directory(), "other", test_geometry(), {std::uint64_t{100}}), FormatError);
}

TEST(Store, RunsRecordParametersStatisticsAndComponents) {
  ScratchDir scratch;
  auto store = ComponentStore::create(scratch.path() / "s", test_geometry());
  auto run = store.begin_run(R"({"command": "extract", "threshold": 0.5})");
  {
    LocalSink sink(store, {"local", run, 2});
    for (std::uint64_t key = 1; key <= 5; ++key)
      sink.commit(make_component(key, test_geometry()));
  }
  store.end_run(run, R"({"collapses": 1234, "peak_memory_bytes": 5e8})");
  auto second = store.begin_run("{}");
  auto runs = store.runs();
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].id, run);
  EXPECT_EQ(runs[0].component_count, 5u);
  EXPECT_EQ(nlohmann::json::parse(runs[0].parameters)["threshold"], 0.5);
  EXPECT_EQ(nlohmann::json::parse(runs[0].statistics)["collapses"], 1234);
  EXPECT_FALSE(runs[0].started.empty());
  EXPECT_FALSE(runs[0].ended.empty());
  EXPECT_EQ(runs[1].id, second);
  EXPECT_TRUE(runs[1].ended.empty());
  EXPECT_EQ(store.find(3)->run, run);
  Query by_run;
  by_run.run = run;
  EXPECT_EQ(store.count(by_run), 5u);
  EXPECT_THROW(store.begin_run("{not json"), InvalidArgument);
  EXPECT_THROW(store.end_run(999, "{}"), InvalidArgument);
}

TEST(Store, SelectionsKeepKeysAndParameters) {
  ScratchDir scratch;
  auto dir = make_store(scratch, 10);
  auto store = ComponentStore::open(dir, OpenMode::read_write);
  store.save_selection("bubbles removed", {30, 3, 12}, R"({"min_volume": 1e6})");
  auto selection = store.load_selection("bubbles removed");
  EXPECT_EQ(selection.keys, (std::vector<std::uint64_t>{30, 3, 12})); // a ranking keeps its order
  EXPECT_EQ(nlohmann::json::parse(selection.parameters)["min_volume"], 1e6);
  Query q;
  q.selection = "bubbles removed";
  auto rows = store.query(q);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].key, 3u);
  q.sort = SortKey::selection;
  rows = store.query(q);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].key, 30u);
  EXPECT_EQ(rows[2].key, 12u);
  q.selection.clear();
  EXPECT_THROW(store.query(q), InvalidArgument); // selection order without a selection
  EXPECT_THROW(store.save_selection("bubbles removed", {3}, "{}"), InvalidArgument);
  store.save_selection("bubbles removed", {6}, "{}", true);
  EXPECT_EQ(store.load_selection("bubbles removed").keys, std::vector<std::uint64_t>{6});
  auto message = message_of<InvalidArgument>([&] { store.save_selection("x", {3, 4}, "{}"); });
  EXPECT_NE(message.find("key 4"), std::string::npos) << message;
  EXPECT_EQ(store.selections().size(), 1u); // the failed one left nothing behind
  Query unknown;
  unknown.selection = "nope";
  message = message_of<InvalidArgument>([&] { store.query(unknown); });
  EXPECT_NE(message.find("bubbles removed"), std::string::npos) << message;
  store.delete_selection("bubbles removed");
  EXPECT_TRUE(store.selections().empty());
  EXPECT_EQ(store.size(), 10u); // selections never delete components
}

TEST(Store, OpeningAndCreatingReportClearErrors) {
  ScratchDir scratch;
  auto missing = scratch.path() / "missing";
  auto message = message_of<IoError>([&] { ComponentStore::open(missing); });
  EXPECT_NE(message.find(missing.string()), std::string::npos) << message;

  std::filesystem::create_directories(scratch.path() / "plain");
  message = message_of<FormatError>([&] { ComponentStore::open(scratch.path() / "plain"); });
  EXPECT_NE(message.find("not a geotandem store"), std::string::npos) << message;

  std::ofstream(scratch.path() / "plain" / "x.txt") << "x";
  EXPECT_THROW(ComponentStore::create(scratch.path() / "plain", test_geometry()), InvalidArgument);

  auto dir = make_store(scratch, 2);
  EXPECT_THROW(ComponentStore::create(dir, test_geometry()), InvalidArgument);
  auto other = test_geometry();
  other.dz = 2.0;
  EXPECT_THROW(ComponentStore::open_or_create(dir, other), InvalidArgument);
  EXPECT_EQ(ComponentStore::open_or_create(dir, test_geometry()).size(), 2u);

  auto info = nlohmann::json::parse(ComponentStore::open(dir).info_json());
  EXPECT_EQ(info["format_version"], store_format_version);
  info["format_version"] = 99;
  std::ofstream(dir / "store.json") << info.dump();
  message = message_of<FormatError>([&] { ComponentStore::open(dir); });
  EXPECT_NE(message.find("99"), std::string::npos) << message;
  std::ofstream(dir / "store.json") << "{ broken";
  EXPECT_THROW(ComponentStore::open(dir), FormatError);

  auto fresh = make_store(scratch, 0, 1, "fresh");
  std::ofstream(fresh / "index.sqlite", std::ios::trunc) << "this is not a database, but long enough to look like one";
  EXPECT_THROW(ComponentStore::open(fresh), FormatError);
}

TEST(Store, ReadOnlyStoresRefuseWritesAndUnknownKeysAreNamed) {
  ScratchDir scratch;
  auto dir = make_store(scratch, 3);
  auto store = ComponentStore::open(dir);
  EXPECT_FALSE(store.writable());
  EXPECT_THROW(store.begin_run("{}"), InvalidArgument);
  EXPECT_THROW(LocalSink(store, {}), InvalidArgument);
  auto message = message_of<InvalidArgument>([&] { store.read(424242); });
  EXPECT_NE(message.find("424242"), std::string::npos) << message;
  // Empty surfaces and triangles naming missing vertices never reach a shard.
  auto writable = ComponentStore::open(dir, OpenMode::read_write);
  LocalSink sink(writable, {"local", std::nullopt, 1});
  mesh::Component empty;
  empty.key = 5;
  EXPECT_THROW(sink.commit(empty), InvalidArgument);
  auto broken = make_component(7, test_geometry());
  broken.surface.triangles[0][1] = 100000;
  EXPECT_THROW(sink.commit(broken), InvalidArgument);
  sink.close();
  EXPECT_EQ(writable.size(), 3u);
}

} // namespace
} // namespace geotandem::store
