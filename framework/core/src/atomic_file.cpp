#include "geotandem/core/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "geotandem/core/error.hpp"

namespace geotandem {
namespace {

std::filesystem::path directory_of(const std::filesystem::path& target) {
  return target.parent_path().empty() ? std::filesystem::path(".") : target.parent_path();
}

void sync_path(const std::filesystem::path& path, int flags, const std::string& what) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) throw IoError("cannot open " + what + " to flush it: " + std::strerror(errno), {path.string()});
  // Some filesystems refuse fsync on directories (EINVAL): the entry is then as durable as it gets.
  const bool failed = ::fsync(fd) != 0 && errno != EINVAL;
  const int error = errno;
  ::close(fd);
  if (failed)
    throw IoError("cannot flush " + what + " to disk: " + std::strerror(error), {path.string()},
                  error == ENOSPC ? "the disk is full" : "");
}

// The process's umask, read without changing it (umask(2) can only set it, which would race with
// other threads creating files): Linux shows it in /proc/self/status. 022 where that is missing.
mode_t current_umask() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("Umask:", 0) == 0) return static_cast<mode_t>(std::stoul(line.substr(6), nullptr, 8));
  return 022;
}

} // namespace

AtomicFile::AtomicFile(std::filesystem::path target, std::ios::openmode mode) : target_(std::move(target)) {
  const auto dir = directory_of(target_);
  // Hidden, so that a listing of the output shows no half-made file; unique, so that two writers
  // of one target each have their own (mkstemp opens it with O_EXCL).
  const std::string pattern = (dir / ("." + target_.filename().string() + ".XXXXXX.tmp")).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = ::mkstemps(name.data(), 4);
  if (fd < 0)
    throw IoError(std::string("cannot create a file in the directory: ") + std::strerror(errno), {dir.string()},
                  errno == ENOSPC ? "the disk is full" : "check that the directory exists and is writable");
  // mkstemp makes it 0600: an output gets the mode an ordinary new file would (0666 less the umask).
  ::fchmod(fd, 0666 & ~current_umask());
  ::close(fd);
  temporary_ = name.data();
  out_.open(temporary_, mode | std::ios::out | std::ios::trunc);
  if (!out_) {
    std::error_code ec;
    std::filesystem::remove(temporary_, ec);
    throw IoError("cannot open the temporary file", {temporary_.string()});
  }
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  out_.close();
  std::error_code ec;
  std::filesystem::remove(temporary_, ec);
}

void AtomicFile::commit(const std::string& what) {
  out_.flush();
  out_.close();
  if (!out_) throw IoError("cannot write " + what, {temporary_.string()}, "is the disk full?");
  sync_path(temporary_, O_RDONLY, what);
  if (::rename(temporary_.c_str(), target_.c_str()) != 0)
    throw IoError("cannot move " + what + " into place: " + std::strerror(errno), {target_.string()});
  committed_ = true;
  sync_path(directory_of(target_), O_RDONLY | O_DIRECTORY, "the directory");
}

void write_file_atomically(const std::filesystem::path& path, const std::string& text, const std::string& what) {
  AtomicFile file(path);
  file.stream() << text;
  file.commit(what);
}

} // namespace geotandem
