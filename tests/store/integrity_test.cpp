// Store integrity: the run identity that refuses mixed resumes, check_store, reruns that write
// damaged records again (also after a shard was cut short), the checks of a record as it is read,
// and the writer lock that guards removal.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "fixtures.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/mesh/measure.hpp"
#include "geotandem/store/check.hpp"
#include "geotandem/store/local_sink.hpp"
#include "scratch.hpp"

namespace geotandem::store {
namespace {

using geotandem::testing::ScratchDir;

void fill(ComponentStore& store, std::uint64_t from, std::uint64_t to, std::optional<std::int64_t> run = {}) {
  LocalSink sink(store, {"local", run, 8});
  for (auto key = from; key <= to; ++key)
    sink.commit(testing::make_component(key, store.geometry()));
  sink.close();
}

void flip_byte(const std::filesystem::path& file, std::uint64_t offset) {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(static_cast<std::streamoff>(offset));
  char c = 0;
  f.read(&c, 1);
  c = static_cast<char>(c ^ 0x21);
  f.seekp(static_cast<std::streamoff>(offset));
  f.write(&c, 1);
}

TEST(StoreIntegrity, RunsOfAnotherIdentityAreRefusedWithEveryDifference) {
  ScratchDir dir;
  auto store = ComponentStore::create(dir.path() / "s", testing::test_geometry());
  store.begin_run(R"({"identity": {"iso": 0.5, "axis": "i", "input": {"size": 10, "mtime_ns": 1}}})");
  EXPECT_TRUE(store.resume_differences(R"({"iso": 0.5, "axis": "i", "input": {"size": 10, "mtime_ns": 1}})").empty());
  auto differences = store.resume_differences(R"({"iso": 0.6, "axis": "i", "input": {"size": 11, "mtime_ns": 1}})");
  ASSERT_EQ(differences.size(), 2u);
  EXPECT_EQ(differences[0], "input.size: 10 in the store, 11 now");
  EXPECT_EQ(differences[1], "iso: 0.5 in the store, 0.6 now");
  EXPECT_THROW(store.begin_run(R"({"identity": {"iso": 0.6, "axis": "i", "input": {"size": 10, "mtime_ns": 1}}})"),
               InvalidArgument);
  EXPECT_EQ(store.runs().size(), 1u) << "a refused run is not recorded";
  // A new key is a difference too (a chain added), and runs without identity are not compared.
  EXPECT_EQ(store.resume_differences(R"({"iso": 0.5, "axis": "i", "input": {"size": 10, "mtime_ns": 1}, "chain": []})")
                .size(),
            1u);
  EXPECT_NO_THROW(store.begin_run(R"({"command": "a test"})"));
  EXPECT_NO_THROW(store.begin_run(R"({"identity": {"iso": 0.5, "axis": "i", "input": {"size": 10, "mtime_ns": 1}}})"));
}

TEST(StoreIntegrity, CheckListsDamagedRecordsAndARerunWritesThemAgain) {
  ScratchDir dir;
  auto store = ComponentStore::create(dir.path() / "s", testing::test_geometry());
  fill(store, 1, 20);
  NullProgress quiet;
  auto clean = check_store(store, quiet, CancelToken{});
  EXPECT_EQ(clean.checked, 20u);
  EXPECT_TRUE(clean.damaged.empty());

  auto row7 = *store.find(7), row12 = *store.find(12);
  flip_byte(dir.path() / "s/shards/local.gts", row7.location.offset + row7.location.length / 2);
  flip_byte(dir.path() / "s/shards/local.gts", row12.location.offset + 3); // the magic
  auto report = check_store(store, quiet, CancelToken{});
  ASSERT_EQ(report.damaged.size(), 2u);
  EXPECT_EQ(report.damaged[0].key, 7u);
  EXPECT_EQ(report.damaged[1].key, 12u);
  EXPECT_NE(report.damaged[0].problem.find("checksum"), std::string::npos) << report.damaged[0].problem;

  LocalSink sink(store, {"local", std::nullopt, 8});
  for (std::uint64_t key = 1; key <= 20; ++key)
    sink.commit(testing::make_component(key, store.geometry()));
  sink.close();
  EXPECT_EQ(sink.redone(), 2u);
  EXPECT_EQ(sink.duplicates(), 18u);
  EXPECT_TRUE(check_store(store, quiet, CancelToken{}).damaged.empty());
  EXPECT_EQ(store.size(), 20u);
  auto surface = store.read(7);
  auto expected = testing::make_component(7, store.geometry());
  EXPECT_EQ(surface.triangles.size(), expected.surface.triangles.size());
}

TEST(StoreIntegrity, ARerunRepairsAShardCutShortUnderTheIndex) {
  ScratchDir dir;
  {
    auto store = ComponentStore::create(dir.path() / "s", testing::test_geometry());
    fill(store, 1, 10);
  }
  const auto shard = dir.path() / "s/shards/local.gts";
  std::filesystem::resize_file(shard, std::filesystem::file_size(shard) - 100);
  auto store = ComponentStore::open(dir.path() / "s", OpenMode::read_write);
  NullProgress quiet;
  auto report = check_store(store, quiet, CancelToken{});
  ASSERT_EQ(report.damaged.size(), 1u);
  EXPECT_EQ(report.damaged[0].key, 10u);
  fill(store, 1, 10); // before: "the shard was truncated or replaced", and no way forward
  EXPECT_TRUE(check_store(store, quiet, CancelToken{}).damaged.empty());
}

// A record is read in pieces (header, points, triangles, checksum) straight into the surface: a
// damaged byte in any piece, and a shard cut inside any piece, is still found and named.
TEST(StoreIntegrity, EveryPieceOfARecordIsCheckedWhenRead) {
  ScratchDir dir;
  {
    auto store = ComponentStore::create(dir.path() / "s", testing::test_geometry());
    fill(store, 1, 6);
  }
  const auto shard = dir.path() / "s/shards/local.gts";
  const auto read_error = [&](std::uint64_t key) -> std::string {
    try {
      ComponentStore::open(dir.path() / "s").read(key);
    } catch (const FormatError& e) {
      return e.what();
    }
    ADD_FAILURE() << "reading component " << key << " did not fail";
    return {};
  };
  const auto last = *ComponentStore::open(dir.path() / "s").find(6); // the shard's last record
  const std::uint64_t points_at = last.location.offset + 40, triangles_at = points_at + 24 * last.location.vertex_count,
                      trailer_at = last.location.offset + last.location.length - 8;
  const std::vector<std::pair<std::uint64_t, std::string>> flips{{last.location.offset + 1, "bad record header"},
                                                                 {last.location.offset + 9, "holds key"},
                                                                 {points_at + 5, "checksum"},
                                                                 {triangles_at + 1, "checksum"},
                                                                 {trailer_at + 2, "checksum"}};
  for (const auto& [offset, problem] : flips) {
    flip_byte(shard, offset);
    const std::string message = read_error(6);
    EXPECT_NE(message.find(problem), std::string::npos) << "byte " << offset << ": " << message;
    EXPECT_NE(message.find("component 6"), std::string::npos) << message;
    flip_byte(shard, offset); // back as it was
  }
  EXPECT_TRUE(testing::same_surface(
      ComponentStore::open(dir.path() / "s").read(6),
      mesh::to_world(testing::make_component(6, testing::test_geometry()).surface, testing::test_geometry())));
  for (const std::uint64_t end : {trailer_at + 3, triangles_at + 5, points_at + 7, last.location.offset + 20}) {
    std::filesystem::resize_file(shard, end); // shorter each time
    const std::string message = read_error(6);
    EXPECT_NE(message.find("truncated"), std::string::npos) << "cut at " << end << ": " << message;
  }
  EXPECT_NO_THROW(ComponentStore::open(dir.path() / "s").read(5));
}

TEST(StoreIntegrity, RemovalWaitsForNoWriterAndKeepsForeignFiles) {
  ScratchDir dir;
  const auto path = dir.path() / "s";
  {
    auto writer = ComponentStore::create(path, testing::test_geometry());
    fill(writer, 1, 3);
    EXPECT_THROW(ComponentStore::remove(path), IoError);
    EXPECT_TRUE(ComponentStore::exists(path));
    auto reader = ComponentStore::open(path); // readers do not take the lock
    EXPECT_EQ(reader.size(), 3u);
  }
  { std::ofstream(path / "notes.txt") << "mine"; }
  EXPECT_THROW(ComponentStore::remove(path), IoError) << "a file the store did not write";
  std::filesystem::remove(path / "notes.txt");
  ComponentStore::remove(path);
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_NO_THROW(ComponentStore::remove(path)) << "nothing to remove is fine";
}

} // namespace
} // namespace geotandem::store
