#pragma once
// Small RAII wrappers around posix_spawn's C structures, shared by the command runner and the
// local backend. We never fork: the runtime's process holds a ZeroMQ context, and forking after
// creating one is unsafe.

#include <spawn.h>
#include <string>
#include <vector>

namespace geotandem::schedulers {

// A pipe whose ends are close-on-exec; the read end is non-blocking.
class Pipe {
public:
  Pipe();
  ~Pipe();
  Pipe(const Pipe&) = delete;
  Pipe& operator=(const Pipe&) = delete;
  int read_end() const noexcept { return fds_[0]; }
  int write_end() const noexcept { return fds_[1]; }
  void close_write() noexcept;

private:
  int fds_[2] = {-1, -1};
};

class SpawnActions {
public:
  SpawnActions();
  ~SpawnActions();
  SpawnActions(const SpawnActions&) = delete;
  SpawnActions& operator=(const SpawnActions&) = delete;
  void open_dev_null(int target);
  void open_for_writing(int target, const std::string& path); // created or truncated, mode 0644
  void dup_to(int fd, int target);
  void change_directory(const std::string& path);
  const posix_spawn_file_actions_t* get() const noexcept { return &actions_; }

private:
  posix_spawn_file_actions_t actions_;
};

class SpawnAttributes {
public:
  explicit SpawnAttributes(bool own_process_group);
  ~SpawnAttributes();
  SpawnAttributes(const SpawnAttributes&) = delete;
  SpawnAttributes& operator=(const SpawnAttributes&) = delete;
  const posix_spawnattr_t* get() const noexcept { return &attributes_; }

private:
  posix_spawnattr_t attributes_;
};

// A NULL-terminated char* array pointing into strings that must outlive it.
class CArgv {
public:
  explicit CArgv(const std::vector<std::string>& strings);
  char* const* data() noexcept { return pointers_.data(); }

private:
  std::vector<char*> pointers_;
};

// Quotes an argument for a POSIX shell with single quotes: 'it'\''s'.
std::string shell_quote(const std::string& text);
// The same, but leaves plain words ([A-Za-z0-9_./=:,+@%-]) alone (for messages and scripts).
std::string shell_quote_if_needed(const std::string& text);

} // namespace geotandem::schedulers
