// AtomicFile: a target appears whole or not at all, and two writers of one target never share a
// temporary (the fixed NAME.part did, and two exports to one path tore).

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "geotandem/core/atomic_file.hpp"
#include "geotandem/core/error.hpp"
#include "scratch.hpp"

namespace geotandem {
namespace {

std::string text_of(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::size_t entries(const std::filesystem::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir))
    ++n;
  return n;
}

TEST(AtomicFile, TwoWritersOfOneTargetEachWriteTheirOwnAndTheLastRenameWins) {
  testing::ScratchDir dir;
  const auto target = dir.path() / "bodies.ply";
  std::ofstream(target) << "an earlier export";
  {
    AtomicFile first(target), second(target);
    EXPECT_NE(first.temporary(), second.temporary());
    EXPECT_EQ(first.temporary().parent_path(), target.parent_path()) << "renamed within one filesystem";
    first.stream() << "header A\n";
    second.stream() << "header B\n";
    first.stream() << "body A\n";
    second.stream() << "body B\n";
    EXPECT_EQ(text_of(target), "an earlier export") << "the target is untouched until a commit";
    first.commit();
    EXPECT_EQ(text_of(target), "header A\nbody A\n");
    second.commit();
  }
  EXPECT_EQ(text_of(target), "header B\nbody B\n");
  EXPECT_EQ(entries(dir.path()), 1u) << "no temporary is left";
}

TEST(AtomicFile, AFileDroppedBeforeItsCommitLeavesNothing) {
  testing::ScratchDir dir;
  const auto target = dir.path() / "report.html";
  {
    AtomicFile file(target);
    file.stream() << "half a report";
    EXPECT_TRUE(std::filesystem::exists(file.temporary()));
  }
  EXPECT_FALSE(std::filesystem::exists(target));
  EXPECT_EQ(entries(dir.path()), 0u);
  EXPECT_THROW(AtomicFile(dir.path() / "missing-dir" / "x"), IoError);
  write_file_atomically(target, "whole");
  EXPECT_EQ(text_of(target), "whole");
}

// The output gets the mode any new file of the process would: 0666 less the umask (mkstemp's 0600
// would hide exports from the user's group; a fixed 0644 would ignore a umask of 077).
TEST(AtomicFile, TheOutputHasTheModeTheUmaskGivesNewFiles) {
  testing::ScratchDir dir;
  for (const mode_t mask : {mode_t{022}, mode_t{077}, mode_t{002}}) {
    const mode_t before = ::umask(mask);
    const auto target = dir.path() / ("out" + std::to_string(mask));
    write_file_atomically(target, "x");
    std::ofstream(dir.path() / "plain") << "x"; // how an ordinary new file comes out
    ::umask(before);
    struct stat made = {};
    struct stat plain = {};
    ASSERT_EQ(::stat(target.c_str(), &made), 0);
    ASSERT_EQ(::stat((dir.path() / "plain").c_str(), &plain), 0);
    EXPECT_EQ(made.st_mode & 0777, plain.st_mode & 0777) << "umask " << std::oct << mask;
    std::filesystem::remove(dir.path() / "plain");
  }
}

} // namespace
} // namespace geotandem
