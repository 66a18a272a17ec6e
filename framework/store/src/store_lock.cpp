// The store's writer lock and removal (--fresh). The process that opens a store for writing (the
// manager of a distributed run, or the single process of a local run) holds an exclusive flock on
// the store directory for as long as the store is open, so a second writer is refused whatever
// the workers (it used to be shared, and two runs with workers both wrote the index); workers
// write their own shards and take no directory lock. Removal takes it too, so it cannot delete a
// store under a running extraction. flock locks end with the process, also when it is killed.

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <set>

#include "geotandem/core/error.hpp"
#include "geotandem/store/writer_lock.hpp"
#include "store_impl.hpp"

namespace geotandem::store {

using namespace detail;

namespace {

// An exclusive flock on `dir`, or the error that says who holds it.
int lock_directory(const std::filesystem::path& dir, const char* busy, const char* what) {
  int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw IoError(std::string("cannot open ") + what + ": " + errno_text(errno), {dir.string()});
  FileHandle handle(fd);
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    int error = errno;
    if (error == EWOULDBLOCK)
      throw IoError(busy, {dir.string()},
                    "wait until it ends (or stop it) and run again to resume, or write to another output directory");
    throw IoError(std::string("cannot lock ") + what + ": " + errno_text(error), {dir.string()});
  }
  return handle.release();
}

} // namespace

namespace detail {

FileHandle lock_store_directory(const std::filesystem::path& dir) {
  return FileHandle(lock_directory(dir, "another process is writing this store", "the store directory"));
}

} // namespace detail

DirectoryLock::~DirectoryLock() {
  if (fd_ >= 0) ::close(fd_); // also releases the flock
}

DirectoryLock& DirectoryLock::operator=(DirectoryLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

DirectoryLock lock_output_directory(const std::filesystem::path& dir) {
  return DirectoryLock(
      lock_directory(dir, "another process is writing this store and its output directory", "the output directory"));
}

void ComponentStore::remove(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::exists(dir, ec)) return;
  if (!std::filesystem::is_directory(dir, ec))
    throw IoError("cannot remove the store: the path is not a directory", {dir.string()});
  // Only what a store holds is deleted: a mistyped path must not cost the user other files.
  static const std::set<std::string> store_files = {
      "store.json",           "store.json.tmp", "index.sqlite",        "index.sqlite-wal", "index.sqlite-shm",
      "index.sqlite-journal", "shards",         "finished-blocks.txt", // the runtime's finished leaves (resume)
      "task-log.tsv"}; // the runtime's task log (geotandem/runtime/task_log.hpp)
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (!store_files.count(entry.path().filename().string()) &&
        !is_store_json_temporary(entry.path().filename().string()))
      throw IoError("will not remove the directory: it holds '" + entry.path().filename().string() +
                        "', which is not part of a store",
                    {dir.string()}, "remove it yourself, or write to another output directory");
  auto lock = lock_store_directory(dir);
  // store.json first: from then on the directory is an interrupted creation, never a store.
  std::filesystem::remove(dir / "store.json", ec);
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    std::filesystem::remove_all(entry.path(), ec);
  if (ec) throw IoError("cannot remove the store: " + ec.message(), {dir.string()});
  std::filesystem::remove(dir, ec);
}

} // namespace geotandem::store
