#pragma once
// The leaves an earlier run finished, kept in STORE/finished-blocks.txt so that a rerun of the same
// extraction (after Ctrl-C, or a manager killed) does not redo them.
//
// "Finished" means: a worker's surface held exactly these leaves and, after its task (an EXTRACT,
// a MERGE or the final pass), held nothing more: every component they contain was dumped, and
// the manager committed those components to the index before it wrote the line. A leaf whose open
// components were merged into a surface that was not emptied is not finished: it is redone. The
// store refuses a run of another identity (block size, isovalue, input...), so the lines of a
// store always describe the tree of the run that resumes.
//
// One line per leaf, "lo0 lo1 lo2 hi0 hi1 hi2" (its cells), appended and synced; a line cut by a
// kill, or a box that is not a leaf of the tree, is ignored.
#include <filesystem>
#include <vector>

#include "geotandem/core/log.hpp"
#include "geotandem/tandem/block_tree.hpp"

namespace geotandem::runtime::detail {

class FinishedBlocks {
public:
  FinishedBlocks(const std::filesystem::path& store_dir, const tandem::BlockTree& tree);
  ~FinishedBlocks();
  FinishedBlocks(const FinishedBlocks&) = delete;
  FinishedBlocks& operator=(const FinishedBlocks&) = delete;

  // The leaves recorded by earlier runs, in tree order.
  std::vector<tandem::NodeId> load(Logger& log);
  // Appends the leaves not recorded yet and syncs the file. Throws IoError when it cannot be
  // written.
  void record(const std::vector<tandem::NodeId>& leaves);

  static constexpr const char* kFileName = "finished-blocks.txt";

private:
  std::filesystem::path path_;
  const tandem::BlockTree& tree_;
  std::vector<char> recorded_; // per node id
  int fd_ = -1;
};

} // namespace geotandem::runtime::detail
