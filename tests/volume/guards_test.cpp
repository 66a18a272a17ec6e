// Input fingerprints (what a store and a rerun compare) and overflow-safe size arithmetic.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <limits>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/fingerprint.hpp"
#include "geotandem/volume/size_guard.hpp"
#include "scratch.hpp"

namespace geotandem::volume {
namespace {

void write_bytes(const std::string& path, std::size_t size, char fill) {
  std::ofstream(path, std::ios::binary) << std::string(size, fill);
}

void set_mtime(const std::string& path, const struct stat& like) {
  timespec times[2] = {like.st_atim, like.st_mtim};
  ASSERT_EQ(::utimensat(AT_FDCWD, path.c_str(), times, 0), 0);
}

TEST(InputFingerprint, ChangesWithContentEvenAtTheSameSizeAndTime) {
  geotandem::testing::ScratchDir dir;
  const auto path = dir.file("cube.bin");
  write_bytes(path, 3 << 20, 'a');
  const auto first = input_fingerprint(path);
  EXPECT_EQ(first["size"], 3u << 20);
  EXPECT_EQ(input_fingerprint(path), first) << "the same file, the same fingerprint";
  struct stat before = {};
  ASSERT_EQ(::stat(path.c_str(), &before), 0);

  // One byte changed in the middle (in a sampled block), the modification time put back.
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp((3 << 20) / 63 * 31);
    f.put('b');
  }
  set_mtime(path, before);
  auto changed = input_fingerprint(path);
  EXPECT_EQ(changed["mtime_ns"], first["mtime_ns"]);
  EXPECT_NE(changed["sampled_checksum"], first["sampled_checksum"]);

  // A description for what is not a file (a synthetic cube, an attribute chain).
  EXPECT_EQ(input_fingerprint("seismic synthetic [64, 64, 64] seed 1")["description"],
            "seismic synthetic [64, 64, 64] seed 1");
}

TEST(SizeGuard, ByteCountsNeverWrap) {
  EXPECT_EQ(checked_byte_count({100, 200, 300}, 4), 24000000u);
  EXPECT_EQ(checked_byte_count({1LL << 31, 1LL << 31, 1}, 2), std::uint64_t{1} << 63);
  EXPECT_FALSE(checked_byte_count({1LL << 31, 1LL << 31, 1}, 4)) << "exactly 2^64 bytes wraps to 0";
  EXPECT_FALSE(checked_byte_count({1LL << 32, 1LL << 32, 1LL << 2}, 4)) << "2^66 bytes";
  EXPECT_FALSE(checked_byte_count({-1, 2, 3}, 4));
  try {
    check_shape_fits({1LL << 31, 1LL << 31, 1}, "the test shape");
    FAIL() << "a shape of 2^64 bytes passed";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("the test shape 2147483648 x 2147483648 x 1"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(check_shape_fits({64, 64, 64}, "a small shape"));
}

} // namespace
} // namespace geotandem::volume
