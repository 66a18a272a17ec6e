#include "posix_spawn_util.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <signal.h>
#include <stdexcept>
#include <unistd.h>

namespace geotandem::schedulers {

namespace {
void check(int rc, const char* what) {
  if (rc != 0) throw std::runtime_error(std::string(what) + ": " + std::strerror(rc));
}
} // namespace

Pipe::Pipe() {
  if (::pipe2(fds_, O_CLOEXEC) != 0) throw std::runtime_error(std::string("pipe2: ") + std::strerror(errno));
  ::fcntl(fds_[0], F_SETFL, ::fcntl(fds_[0], F_GETFL) | O_NONBLOCK);
}
Pipe::~Pipe() {
  for (int fd : fds_)
    if (fd >= 0) ::close(fd);
}
void Pipe::close_write() noexcept {
  if (fds_[1] >= 0) ::close(fds_[1]);
  fds_[1] = -1;
}

SpawnActions::SpawnActions() {
  check(::posix_spawn_file_actions_init(&actions_), "posix_spawn_file_actions_init");
}
SpawnActions::~SpawnActions() {
  ::posix_spawn_file_actions_destroy(&actions_);
}
void SpawnActions::open_dev_null(int target) {
  check(::posix_spawn_file_actions_addopen(&actions_, target, "/dev/null", O_RDWR, 0), "posix_spawn addopen");
}
void SpawnActions::open_for_writing(int target, const std::string& path) {
  check(::posix_spawn_file_actions_addopen(&actions_, target, path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644),
        "posix_spawn addopen");
}
void SpawnActions::dup_to(int fd, int target) {
  check(::posix_spawn_file_actions_adddup2(&actions_, fd, target), "posix_spawn adddup2");
}
void SpawnActions::change_directory(const std::string& path) {
  check(::posix_spawn_file_actions_addchdir_np(&actions_, path.c_str()), "posix_spawn addchdir");
}

SpawnAttributes::SpawnAttributes(bool own_process_group) {
  check(::posix_spawnattr_init(&attributes_), "posix_spawnattr_init");
  short flags = POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF;
  if (own_process_group) {
    flags |= POSIX_SPAWN_SETPGROUP;
    check(::posix_spawnattr_setpgroup(&attributes_, 0), "posix_spawnattr_setpgroup");
  }
  // The child starts with no blocked signals and default handlers for the ones a caller may have
  // changed (a runtime that ignores SIGPIPE or handles SIGINT must not pass that on).
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  for (int sig : {SIGINT, SIGTERM, SIGPIPE, SIGHUP, SIGCHLD, SIGQUIT, SIGUSR1, SIGUSR2})
    sigaddset(&defaults, sig);
  check(::posix_spawnattr_setsigmask(&attributes_, &none), "posix_spawnattr_setsigmask");
  check(::posix_spawnattr_setsigdefault(&attributes_, &defaults), "posix_spawnattr_setsigdefault");
  check(::posix_spawnattr_setflags(&attributes_, flags), "posix_spawnattr_setflags");
}
SpawnAttributes::~SpawnAttributes() {
  ::posix_spawnattr_destroy(&attributes_);
}

CArgv::CArgv(const std::vector<std::string>& strings) {
  pointers_.reserve(strings.size() + 1);
  for (const auto& s : strings)
    pointers_.push_back(const_cast<char*>(s.c_str()));
  pointers_.push_back(nullptr);
}

std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) {
    if (c == '\'')
      quoted += "'\\''";
    else
      quoted += c;
  }
  return quoted + "'";
}

std::string shell_quote_if_needed(const std::string& text) {
  if (text.empty()) return "''";
  for (char c : text) {
    bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                 std::strchr("_./=:,+@%-", c) != nullptr;
    if (!plain) return shell_quote(text);
  }
  return text;
}

} // namespace geotandem::schedulers
