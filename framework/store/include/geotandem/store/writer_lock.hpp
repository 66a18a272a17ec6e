#pragma once
// One writer per store, whatever the workers. The process that owns a run (the manager of a
// distributed run, or the single process of a local one) holds an exclusive flock on the store
// directory from the moment it opens the store for writing until it closes it, after its workers
// have ended (ComponentStore holds it; see docs/store-format.md). Workers only append to their own
// shards and take no directory lock. A `run-workflow` also locks its output directory for the
// whole run, before it writes anything there (the ground truth, the input's copy, the attribute
// cube, state.json), with the lock below. flock locks end with the process, also when it is killed,
// so a dead run never leaves a stale lock.

#include <filesystem>

namespace geotandem::store {

// An exclusive flock on a directory, released when the object is destroyed.
class DirectoryLock {
public:
  DirectoryLock() = default;
  explicit DirectoryLock(int fd) : fd_(fd) {}
  ~DirectoryLock();
  DirectoryLock(DirectoryLock&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  DirectoryLock& operator=(DirectoryLock&& other) noexcept;
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;
  bool held() const { return fd_ >= 0; }

private:
  int fd_ = -1;
};

// Locks a run's output directory (which must exist). Throws IoError ("another process is writing
// this store and its output directory", exit 3) when another process holds it.
DirectoryLock lock_output_directory(const std::filesystem::path& dir);

} // namespace geotandem::store
