// The finished leaves of earlier runs (finished_blocks.hpp).
#include "finished_blocks.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "geotandem/core/error.hpp"

namespace geotandem::runtime::detail {

namespace {

using Cells = std::array<std::int64_t, 6>;

Cells cells_of(const volume::Box& b) {
  return {b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]};
}

} // namespace

FinishedBlocks::FinishedBlocks(const std::filesystem::path& store_dir, const tandem::BlockTree& tree)
    : path_(store_dir / kFileName), tree_(tree), recorded_(tree.size(), 0) {}

FinishedBlocks::~FinishedBlocks() {
  if (fd_ >= 0) ::close(fd_);
}

std::vector<tandem::NodeId> FinishedBlocks::load(Logger& log) {
  std::ifstream in(path_);
  if (!in) return {};
  std::map<Cells, tandem::NodeId> by_cells;
  for (tandem::NodeId leaf : tree_.leaves())
    by_cells.emplace(cells_of(tree_.node(leaf).cells), leaf);
  std::vector<char>& seen = recorded_;
  std::size_t ignored = 0;
  std::string line;
  while (std::getline(in, line)) {
    if (in.eof()) { // no newline: a line cut by a kill
      ++ignored;
      break;
    }
    std::istringstream fields(line);
    Cells c{};
    for (auto& v : c)
      fields >> v;
    std::string rest;
    auto it = by_cells.find(c);
    if (fields.fail() || (fields >> rest) || it == by_cells.end()) {
      ++ignored;
      continue;
    }
    seen[static_cast<std::size_t>(it->second)] = 1;
  }
  if (ignored) log.warning(path_.string() + ": " + std::to_string(ignored) + " line(s) that name no block ignored");
  std::vector<tandem::NodeId> out;
  for (tandem::NodeId leaf : tree_.leaves())
    if (seen[static_cast<std::size_t>(leaf)]) out.push_back(leaf);
  return out;
}

void FinishedBlocks::record(const std::vector<tandem::NodeId>& leaves) {
  std::string text;
  for (tandem::NodeId leaf : leaves) {
    char& done = recorded_.at(static_cast<std::size_t>(leaf));
    if (done) continue;
    done = 1;
    const Cells c = cells_of(tree_.node(leaf).cells);
    text += std::to_string(c[0]) + ' ' + std::to_string(c[1]) + ' ' + std::to_string(c[2]) + ' ' +
            std::to_string(c[3]) + ' ' + std::to_string(c[4]) + ' ' + std::to_string(c[5]) + '\n';
  }
  if (text.empty()) return;
  if (fd_ < 0) {
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd_ < 0)
      throw IoError(std::string("cannot write the finished blocks: ") + std::strerror(errno), {path_.string()},
                    "check that the store directory is writable");
  }
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd_, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw IoError(std::string("cannot write the finished blocks: ") + std::strerror(errno), {path_.string()},
                    "free some disk space; rerunning resumes");
    written += static_cast<std::size_t>(n);
  }
  if (::fdatasync(fd_) != 0)
    throw IoError(std::string("cannot sync the finished blocks: ") + std::strerror(errno), {path_.string()});
}

} // namespace geotandem::runtime::detail
