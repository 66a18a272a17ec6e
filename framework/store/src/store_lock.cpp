// The store's writer lock and removal (--fresh). A process that opens a store for writing holds a
// shared flock on the store directory for as long as the store is open; removal takes it
// exclusively, so it cannot delete a store under a running extraction (which would then report a
// false "shard is damaged"). flock locks end with the process, also when it is killed.

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <set>

#include "geotandem/core/error.hpp"
#include "store_impl.hpp"

namespace geotandem::store {

using namespace detail;

namespace detail {

FileHandle lock_store_directory(const std::filesystem::path& dir, bool exclusive) {
  int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw IoError("cannot open the store directory: " + errno_text(errno), {dir.string()});
  FileHandle handle(fd);
  if (::flock(fd, (exclusive ? LOCK_EX : LOCK_SH) | LOCK_NB) != 0) {
    int error = errno;
    if (error == EWOULDBLOCK)
      throw IoError(exclusive ? "another process is writing this store"
                              : "another process is removing or creating this store",
                    {dir.string()}, "wait until it ends (or stop it), or write to another output directory");
    throw IoError("cannot lock the store directory: " + errno_text(error), {dir.string()});
  }
  return handle;
}

void share_store_lock(const FileHandle& lock, const std::filesystem::path& dir) {
  // Nobody else holds a lock on the directory while this one is exclusive, so this cannot block.
  if (::flock(lock.get(), LOCK_SH | LOCK_NB) != 0)
    throw IoError("cannot lock the store directory: " + errno_text(errno), {dir.string()});
}

} // namespace detail

void ComponentStore::remove(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::exists(dir, ec)) return;
  if (!std::filesystem::is_directory(dir, ec))
    throw IoError("cannot remove the store: the path is not a directory", {dir.string()});
  // Only what a store holds is deleted: a mistyped path must not cost the user other files.
  static const std::set<std::string> store_files = {
      "store.json",           "store.json.tmp", "index.sqlite",       "index.sqlite-wal", "index.sqlite-shm",
      "index.sqlite-journal", "shards",         "finished-blocks.txt"}; // the runtime's finished leaves (resume)
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (!store_files.count(entry.path().filename().string()))
      throw IoError("will not remove the directory: it holds '" + entry.path().filename().string() +
                        "', which is not part of a store",
                    {dir.string()}, "remove it yourself, or write to another output directory");
  auto lock = lock_store_directory(dir, true);
  // store.json first: from then on the directory is an interrupted creation, never a store.
  std::filesystem::remove(dir / "store.json", ec);
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    std::filesystem::remove_all(entry.path(), ec);
  if (ec) throw IoError("cannot remove the store: " + ec.message(), {dir.string()});
  std::filesystem::remove(dir, ec);
}

} // namespace geotandem::store
