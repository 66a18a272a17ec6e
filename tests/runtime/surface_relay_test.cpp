// The manager's relay of partial surfaces (src/surface_relay.hpp) past its memory budget: the
// surfaces waiting for their MERGE go to files and come back byte for byte, the files go when the
// surfaces do, a damaged file is a clear error, and a directory that cannot be written leaves the
// surfaces in memory with a warning instead of losing them.
#include <gtest/gtest.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "../../framework/runtime/src/surface_relay.hpp"
#include "geotandem/core/error.hpp"
#include "scratch.hpp"

namespace geotandem::runtime::detail {
namespace {

using geotandem::testing::ScratchDir;

std::vector<std::byte> random_bytes(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<std::byte> bytes(n);
  for (auto& b : bytes)
    b = static_cast<std::byte>(rng());
  return bytes;
}

// One SEND from `token`, in chunks of 100 bytes, kept for `transfer`.
std::optional<std::string> arrive(SurfaceRelay& relay, const std::string& token, TransferId transfer,
                                  const std::vector<std::byte>& bytes) {
  relay.begin_inbound(token);
  for (std::size_t offset = 0; offset < bytes.size(); offset += 100) {
    const std::size_t n = std::min<std::size_t>(100, bytes.size() - offset);
    EXPECT_EQ(relay.chunk_in(token, offset, std::span(bytes).subspan(offset, n)), std::nullopt);
  }
  std::uint64_t size = 0;
  EXPECT_EQ(relay.end_inbound(token, bytes.size(), surface_checksum(bytes), size), std::nullopt);
  EXPECT_EQ(size, bytes.size());
  auto warning = relay.keep(token, transfer);
  relay.forget(token);
  return warning;
}

// The MERGE of `transfer` to `token`, every chunk sent at once: the bytes the worker receives.
std::vector<std::byte> depart(SurfaceRelay& relay, const std::string& token, TransferId transfer) {
  const SurfaceRelay::Header h = relay.begin_outbound(token, transfer);
  std::vector<std::byte> out;
  for (std::uint64_t credits = 0; out.size() < h.total; credits = kChunkWindow)
    relay.pump(token, credits, [&](std::uint64_t offset, std::span<const std::byte> piece) {
      EXPECT_EQ(offset, out.size());
      out.insert(out.end(), piece.begin(), piece.end());
    });
  EXPECT_EQ(surface_checksum(out), h.checksum);
  return out;
}

std::size_t files_in(const std::filesystem::path& dir) {
  if (!std::filesystem::exists(dir)) return 0;
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir), {}));
}

TEST(SurfaceRelay, SurfacesPastTheBudgetWaitOnDiskAndComeBackWhole) {
  ScratchDir dir;
  const std::filesystem::path spill = dir.file("store.relay");
  const auto a = random_bytes(1500, 1), b = random_bytes(2500, 2), c = random_bytes(700, 3);
  {
    SurfaceRelay relay(1 << 20, 256, 2000, spill);
    EXPECT_EQ(arrive(relay, "w1", 1, a), std::nullopt); // 1500 held
    EXPECT_EQ(arrive(relay, "w2", 2, b), std::nullopt); // would be 4000: on disk
    EXPECT_EQ(arrive(relay, "w1", 3, c), std::nullopt); // 2200: on disk
    EXPECT_EQ(relay.usage().held, 1500u);
    EXPECT_EQ(relay.usage().spilled, 2u);
    EXPECT_EQ(relay.usage().spilled_bytes, 3200u);
    EXPECT_EQ(files_in(spill), 2u);

    EXPECT_EQ(depart(relay, "w3", 2), b); // read back, its file removed
    EXPECT_EQ(files_in(spill), 1u);
    EXPECT_EQ(depart(relay, "w3", 1), a); // from memory
    EXPECT_EQ(relay.usage().held, 0u);
    EXPECT_EQ(relay.usage().peak_held, 1500u);

    // A target that died: its surface's file goes with it.
    relay.drop_kept([](TransferId t) { return t == 3; });
    EXPECT_EQ(files_in(spill), 0u);
    EXPECT_THROW(relay.begin_outbound("w3", 3), std::logic_error);

    EXPECT_EQ(arrive(relay, "w2", 4, b), std::nullopt); // 2500 > 2000 with nothing held: on disk
    EXPECT_EQ(files_in(spill), 1u);
  }
  EXPECT_FALSE(std::filesystem::exists(spill)) << "the relay's files outlived it";
}

TEST(SurfaceRelay, FilesLeftByAKilledManagerGoAndOtherFilesStay) {
  ScratchDir dir;
  const std::filesystem::path spill = dir.file("store.relay");
  std::filesystem::create_directories(spill);
  std::ofstream(spill / "transfer-17.surface") << "left behind";
  std::ofstream(spill / "notes.txt") << "the user's";
  SurfaceRelay relay(1 << 20, 256, 0, spill);
  EXPECT_FALSE(std::filesystem::exists(spill / "transfer-17.surface"));
  EXPECT_TRUE(std::filesystem::exists(spill / "notes.txt"));
}

TEST(SurfaceRelay, AWaitingSurfaceDamagedOnDiskIsAClearErrorNamingItsFile) {
  ScratchDir dir;
  const std::filesystem::path spill = dir.file("store.relay");
  SurfaceRelay relay(1 << 20, 256, 0, spill);
  const auto a = random_bytes(900, 4);
  EXPECT_EQ(arrive(relay, "w1", 7, a), std::nullopt);
  const std::filesystem::path file = spill / "transfer-7.surface";
  ASSERT_TRUE(std::filesystem::exists(file));
  {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(450);
    f.put('\x5a' ^ static_cast<char>(a[450]));
  }
  try {
    relay.begin_outbound("w2", 7);
    FAIL() << "a damaged surface was sent";
  } catch (const IoError& e) {
    const std::string text = e.what();
    EXPECT_NE(text.find(file.string()), std::string::npos) << text;
    EXPECT_NE(text.find("checksum"), std::string::npos) << text;
    EXPECT_NE(text.find("rerun"), std::string::npos) << text;
  }

  EXPECT_EQ(arrive(relay, "w1", 8, a), std::nullopt);
  std::filesystem::resize_file(spill / "transfer-8.surface", 100);
  try {
    relay.begin_outbound("w2", 8);
    FAIL() << "a truncated surface was sent";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("not the 900 bytes written"), std::string::npos) << e.what();
  }
}

TEST(SurfaceRelay, ADirectoryThatCannotBeWrittenKeepsTheSurfacesInMemoryWithOneWarning) {
  ScratchDir dir;
  std::ofstream(dir.file("a-file")) << "x";
  const std::filesystem::path spill = std::filesystem::path(dir.file("a-file")) / "store.relay";
  SurfaceRelay relay(1 << 20, 256, 0, spill);
  const auto a = random_bytes(600, 5), b = random_bytes(800, 6);
  const std::optional<std::string> warning = arrive(relay, "w1", 1, a);
  ASSERT_TRUE(warning.has_value());
  EXPECT_NE(warning->find("stay in memory"), std::string::npos) << *warning;
  EXPECT_NE(warning->find(spill.string()), std::string::npos) << *warning;
  EXPECT_EQ(arrive(relay, "w1", 2, b), std::nullopt) << "warned twice";
  EXPECT_EQ(relay.usage().spilled, 0u);
  EXPECT_EQ(relay.usage().held, 1400u);
  EXPECT_EQ(depart(relay, "w2", 1), a);
  EXPECT_EQ(depart(relay, "w2", 2), b);
}

// A full disk: the surface's file is /dev/full (through a link), whose writes fail with ENOSPC
// when they are flushed. The surface stays in memory, the warning says why, and no file is left.
TEST(SurfaceRelay, AFullDiskKeepsTheSurfaceInMemory) {
  ASSERT_TRUE(std::filesystem::exists("/dev/full")) << "Linux's /dev/full is needed for a real ENOSPC";
  ScratchDir dir;
  const std::filesystem::path spill = dir.file("store.relay");
  SurfaceRelay relay(1 << 20, 256, 0, spill);
  std::filesystem::create_directories(spill);
  std::filesystem::create_symlink("/dev/full", spill / "transfer-3.surface");
  const auto a = random_bytes(5000, 7);
  const std::optional<std::string> warning = arrive(relay, "w1", 3, a);
  ASSERT_TRUE(warning.has_value());
  EXPECT_NE(warning->find(std::strerror(ENOSPC)), std::string::npos) << *warning;
  EXPECT_EQ(relay.usage().spilled, 0u);
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(spill / "transfer-3.surface")));
  EXPECT_EQ(depart(relay, "w2", 3), a);
}

} // namespace
} // namespace geotandem::runtime::detail
