// AtomicFile: a target appears whole or not at all, and two writers of one target never share a
// temporary (the fixed NAME.part did, and two exports to one path tore).

#include <gtest/gtest.h>

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

} // namespace
} // namespace geotandem
