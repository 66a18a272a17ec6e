// Local workers as child processes (launcher.hpp).
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>
#include <utility>

#include "geotandem/core/error.hpp"
#include "geotandem/runtime/launcher.hpp"

extern char** environ;

namespace geotandem::runtime {

LocalLauncher::~LocalLauncher() {
  stop_all(2.0);
}

void LocalLauncher::launch(const std::vector<std::string>& argv, const std::string& token) {
  if (argv.empty()) throw InvalidArgument("local launcher: an empty command line", {.worker = token});
  std::vector<char*> args;
  for (const std::string& a : argv)
    args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  // The worker learns its manager's pid, so that it ends with it (worker.cpp, PR_SET_PDEATHSIG)
  // rather than writing to the store for a heartbeat timeout after a SIGKILL of the manager.
  std::vector<std::string> env_text{std::string(manager_pid_variable) + "=" + std::to_string(::getpid())};
  for (char** e = environ; e && *e; ++e)
    if (std::strncmp(*e, manager_pid_variable, std::strlen(manager_pid_variable)) != 0 ||
        (*e)[std::strlen(manager_pid_variable)] != '=')
      env_text.emplace_back(*e);
  std::vector<char*> env;
  for (std::string& e : env_text)
    env.push_back(e.data());
  env.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0].c_str(), nullptr, nullptr, args.data(), env.data());
  if (rc != 0)
    throw IoError("cannot start worker " + argv[0] + ": " + std::strerror(rc), {.file = argv[0], .worker = token},
                  "check that the geotandem executable exists and is executable");
  children_.push_back({pid, token});
}

void LocalLauncher::reap() {
  std::erase_if(children_, [this](const Child& c) {
    int status = 0;
    const pid_t r = waitpid(c.pid, &status, WNOHANG);
    const bool gone = r == c.pid || (r < 0 && errno == ECHILD);
    if (gone) ended_.push_back(c.token);
    return gone;
  });
}

std::size_t LocalLauncher::running() {
  reap();
  return children_.size();
}

std::vector<std::string> LocalLauncher::ended() {
  reap();
  return std::exchange(ended_, {});
}

std::vector<pid_t> LocalLauncher::pids() {
  reap();
  std::vector<pid_t> out;
  for (const Child& c : children_)
    out.push_back(c.pid);
  return out;
}

void LocalLauncher::stop_all(double grace_seconds) {
  reap();
  if (children_.empty()) return;
  for (const Child& c : children_) {
    kill(c.pid, SIGCONT); // a stopped worker would never see SIGTERM
    kill(c.pid, SIGTERM);
  }
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(grace_seconds);
  while (!children_.empty() && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    reap();
  }
  for (const Child& c : children_)
    kill(c.pid, SIGKILL);
  for (const Child& c : children_)
    waitpid(c.pid, nullptr, 0);
  children_.clear();
}

} // namespace geotandem::runtime
