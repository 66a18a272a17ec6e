#include "geotandem/schedulers/command_runner.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "posix_spawn_util.hpp"

extern char** environ;

namespace geotandem::schedulers {

std::string describe_command(const std::vector<std::string>& argv) {
  std::string text;
  for (const auto& arg : argv) {
    if (!text.empty()) text += ' ';
    text += shell_quote_if_needed(arg);
  }
  return text;
}

namespace {

// Reads what is available on fd into out; returns false at end of file or error.
bool drain(int fd, std::string& out) {
  char buffer[8192];
  for (;;) {
    ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n > 0) {
      out.append(buffer, static_cast<std::size_t>(n));
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return true;
    return false;
  }
}

void record_exit(int status, CommandResult& result) {
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
}

void wait_blocking(pid_t pid, int& status, bool& lost) {
  pid_t done;
  do {
    done = ::waitpid(pid, &status, 0);
  } while (done < 0 && errno == EINTR);
  if (done < 0) lost = true;
}

} // namespace

CommandResult ProcessCommandRunner::run(const std::vector<std::string>& argv, std::chrono::milliseconds timeout) {
  CommandResult result;
  if (argv.empty()) {
    result.spawn_error = "empty command";
    return result;
  }
  Pipe out_pipe, err_pipe;
  SpawnActions actions;
  actions.open_dev_null(STDIN_FILENO);
  actions.dup_to(out_pipe.write_end(), STDOUT_FILENO);
  actions.dup_to(err_pipe.write_end(), STDERR_FILENO);
  // Pipe ends are close-on-exec, so the child keeps only its 1 and 2.
  SpawnAttributes attributes(/*own_process_group=*/true);
  CArgv cargv(argv);
  pid_t pid = -1;
  int rc = ::posix_spawnp(&pid, argv[0].c_str(), actions.get(), attributes.get(), cargv.data(), environ);
  if (rc != 0) {
    result.spawn_error = rc == ENOENT ? "'" + argv[0] + "' not found on PATH" : std::strerror(rc);
    return result;
  }
  out_pipe.close_write();
  err_pipe.close_write();

  const auto deadline = std::chrono::steady_clock::now() + timeout;
  bool out_open = true, err_open = true, exited = false, status_lost = false;
  int status = 0;
  while (out_open || err_open || !exited) {
    if (!exited) {
      pid_t done = ::waitpid(pid, &status, WNOHANG);
      if (done == pid) exited = true;
      if (done < 0 && errno == ECHILD) { // SIGCHLD ignored in this process: the status is gone
        exited = true;
        status_lost = true;
      }
    }
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) { // not the rounded milliseconds below: they would stop up to 1 ms early
      result.timed_out = true;
      break;
    }
    // Rounded up, so that the last wait reaches the deadline rather than stopping short of it.
    auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - now);
    if (exited && !out_open && !err_open) break;
    pollfd fds[2] = {{out_pipe.read_end(), POLLIN, 0}, {err_pipe.read_end(), POLLIN, 0}};
    if (!out_open) fds[0].fd = -1;
    if (!err_open) fds[1].fd = -1;
    // Short waits while the child runs, so that its exit is noticed even if a grandchild
    // keeps the pipes open; the deadline bounds everything.
    int wait_ms = static_cast<int>(std::min<long long>(left.count(), (out_open || err_open) ? 50 : 10));
    int ready = ::poll(fds, 2, wait_ms);
    if (ready < 0 && errno != EINTR) break;
    if (out_open && fds[0].revents) out_open = drain(out_pipe.read_end(), result.out);
    if (err_open && fds[1].revents) err_open = drain(err_pipe.read_end(), result.err);
    // Once the command has exited, a grandchild that still holds the pipes (a daemon it started)
    // must not make us wait: take what is there and stop.
    if (exited && (out_open || err_open) && ready == 0) break;
  }
  if (result.timed_out) {
    ::kill(-pid, SIGKILL); // the whole process group: a hanging client and whatever it started
    if (!exited) wait_blocking(pid, status, status_lost);
    drain(out_pipe.read_end(), result.out);
    drain(err_pipe.read_end(), result.err);
    return result;
  }
  if (!exited) wait_blocking(pid, status, status_lost);
  if (status_lost) {
    result.spawn_error = "its exit status was lost (this process ignores SIGCHLD; do not set it to SIG_IGN)";
    return result;
  }
  record_exit(status, result);
  return result;
}

} // namespace geotandem::schedulers
