// Kill a writing process with SIGKILL at random moments: the store must reopen, list every
// component committed before (the count never drops), read each one back with a valid checksum,
// and hold no key twice. The writer is a separate helper executable (store_crash_writer).

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <random>
#include <set>
#include <thread>

#include "fixtures.hpp"
#include "geotandem/mesh/measure.hpp"
#include "geotandem/store/store.hpp"
#include "scratch.hpp"
#include "test_paths.hpp"

extern char** environ;

namespace geotandem::store {
namespace {

using geotandem::testing::ScratchDir;

constexpr std::uint64_t key_count = 150;

struct Writer {
  pid_t pid = -1;
  int out = -1; // read end of the writer's stdout
};

Writer spawn_writer(const std::filesystem::path& dir, std::uint64_t seed, std::size_t batch) {
  std::vector<std::string> args = {test_paths::store_crash_writer(), dir.string(), std::to_string(seed),
                                   std::to_string(batch), std::to_string(key_count)};
  std::vector<char*> argv;
  for (auto& a : args)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) {
    ADD_FAILURE() << "pipe";
    return {};
  }
  Writer writer;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
  int rc = posix_spawn(&writer.pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[1]);
  writer.out = pipe_fds[0];
  EXPECT_EQ(rc, 0) << "cannot start " << argv[0];
  return writer;
}

// True once the process has ended (it stays waitable).
bool has_exited(pid_t pid) {
  siginfo_t info{};
  return ::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) != 0 || info.si_pid != 0;
}

// Waits (at most `timeout_ms`) for the writer to say it has opened the store.
bool wait_until_open(const Writer& writer, int timeout_ms = 30000) {
  pollfd p{writer.out, POLLIN, 0};
  if (::poll(&p, 1, timeout_ms) <= 0) return false;
  char text[5] = {};
  return ::read(writer.out, text, 4) == 4 && std::string(text) == "open";
}

int wait_for(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

// Everything a reader may rely on after a crash. Returns the number of components.
std::uint64_t check_store(const std::filesystem::path& dir) {
  // Read-write: the first opener after a crash is the one that recovers SQLite's WAL.
  auto store = ComponentStore::open(dir, OpenMode::read_write);
  auto rows = store.query();
  std::set<std::uint64_t> keys;
  const auto geometry = testing::test_geometry();
  for (const auto& row : rows) {
    EXPECT_TRUE(keys.insert(row.key).second) << "key " << row.key << " listed twice";
    EXPECT_GE(row.key, 1u);
    EXPECT_LE(row.key, key_count);
    auto expected = testing::make_component(row.key, geometry, row.key % 10 == 0 ? 3 : 1);
    mesh::SurfaceMesh surface;
    EXPECT_NO_THROW(surface = store.read(row)) << "key " << row.key;
    EXPECT_TRUE(testing::same_surface(surface, mesh::to_world(expected.surface, geometry))) << "key " << row.key;
    EXPECT_TRUE(testing::same_stats(row.stats, expected.stats)) << "key " << row.key;
  }
  if (!rows.empty()) {
    EXPECT_GE(std::filesystem::file_size(shard_path(dir, "local")), store.indexed_end("local"));
  }
  return rows.size();
}

TEST(StoreCrash, SigkillAtRandomMomentsLosesNothingCommitted) {
  ScratchDir scratch;
  const auto dir = scratch.path() / "store";
  std::mt19937_64 rng(7);
  std::uint64_t previous = 0, total_bytes = 0;
  for (std::uint64_t key = 1; key <= key_count; ++key) {
    auto c = testing::make_component(key, testing::test_geometry(), key % 10 == 0 ? 3 : 1);
    total_bytes += 48 + 24 * c.surface.points.size() + 12 * c.surface.triangles.size();
  }
  int kills_with_progress = 0;
  for (int round = 0; round < 14; ++round) {
    auto writer = spawn_writer(dir, static_cast<std::uint64_t>(round), 1 + static_cast<std::size_t>(round % 4));
    ASSERT_GT(writer.pid, 0);
    // The first rounds die during start-up or store creation; the others while committing.
    if (round < 2) {
      // Somewhere in start-up or store creation, at the latest when the store is open.
      wait_until_open(writer, static_cast<int>(rng() % 400));
    } else {
      // Kill at a random point of progress rather than of time, so that the test means the same
      // on a slow disk and a fast one: wait until the shard passes a random size, then a little.
      ASSERT_TRUE(wait_until_open(writer)) << "round " << round << ": the writer never opened the store";
      const auto shard = shard_path(dir, "local");
      std::error_code ec;
      const std::uint64_t base = std::filesystem::exists(shard) ? std::filesystem::file_size(shard) : 0;
      const std::uint64_t target = base + rng() % (total_bytes / 16);
      for (int i = 0; i < 300000; ++i) {
        auto size = std::filesystem::file_size(shard, ec);
        if ((!ec && size >= target) || has_exited(writer.pid)) break;
        std::this_thread::sleep_for(std::chrono::microseconds(50));
      }
      std::this_thread::sleep_for(std::chrono::microseconds(rng() % 2000));
    }
    ::kill(writer.pid, SIGKILL);
    int status = wait_for(writer.pid);
    ::close(writer.out);
    ASSERT_TRUE((WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) || (WIFEXITED(status) && WEXITSTATUS(status) == 0))
        << "round " << round << ": the writer failed by itself (status " << status << ")";
    if (!ComponentStore::exists(dir)) {
      EXPECT_EQ(previous, 0u) << "round " << round << ": store.json vanished";
      continue;
    }
    auto count = check_store(dir);
    if (std::getenv("STORE_CRASH_VERBOSE")) std::cerr << "round " << round << ": " << count << " components\n";
    EXPECT_GE(count, previous) << "round " << round << ": components were lost";
    if (count > previous) ++kills_with_progress;
    previous = count;
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_GT(kills_with_progress, 2) << "the kills came too early or too late to test anything";
  // A last writer runs to the end: every key is there once, and no torn or unindexed byte is left.
  auto writer = spawn_writer(dir, 99, 8);
  int status = wait_for(writer.pid);
  ::close(writer.out);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  EXPECT_EQ(check_store(dir), key_count);
  auto store = ComponentStore::open(dir);
  EXPECT_EQ(std::filesystem::file_size(shard_path(dir, "local")), store.indexed_end("local"));
}

} // namespace
} // namespace geotandem::store
