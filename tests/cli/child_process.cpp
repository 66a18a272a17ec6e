#include "child_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_paths.hpp"
#include <chrono>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace geotandem::testing {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

int exit_code_of(int status) {
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

} // namespace

Child::Child(const std::string& scratch, const std::vector<std::string>& args, unsigned long address_space_bytes) {
  static int counter = 0;
  const std::string base = scratch + "/child-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  out_path_ = base + ".out";
  err_path_ = base + ".err";
  std::vector<std::string> argv_text{test_paths::binary()};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv; // built before fork: the child only calls async-signal-safe functions
  for (auto& a : argv_text)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_ = ::fork();
  if (pid_ < 0) throw std::runtime_error("fork failed");
  if (pid_ == 0) {
    int in = ::open("/dev/null", O_RDONLY);
    int out = ::open(out_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    int err = ::open(err_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in < 0 || out < 0 || err < 0) ::_exit(127);
    ::dup2(in, 0);
    ::dup2(out, 1);
    ::dup2(err, 2);
    if (address_space_bytes) {
      rlimit limit{address_space_bytes, address_space_bytes};
      ::setrlimit(RLIMIT_AS, &limit);
    }
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
}

Child::~Child() {
  if (!reaped_ && pid_ > 0) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
}

std::optional<int> Child::wait_for(double seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  for (;;) {
    if (reaped_) return exit_code_; // asked again after the end: the same answer, not a 30 s wait
    int status = 0;
    pid_t done = ::waitpid(pid_, &status, WNOHANG);
    if (done == pid_) {
      reaped_ = true;
      exit_code_ = exit_code_of(status);
      return exit_code_;
    }
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

void Child::signal(int sig) const {
  if (!reaped_) ::kill(pid_, sig); // a reaped child's pid may already be another process's
}

std::string Child::out() const {
  return slurp(out_path_);
}

std::string Child::err() const {
  return slurp(err_path_);
}

ChildResult run_child(const std::string& scratch, const std::vector<std::string>& args, double seconds,
                      unsigned long address_space_bytes) {
  Child child(scratch, args, address_space_bytes);
  ChildResult result;
  auto code = child.wait_for(seconds);
  if (!code) {
    result.hung = true;
    child.signal(SIGKILL);
    code = child.wait_for(30);
  }
  result.exit_code = code ? *code : -1;
  result.out = child.out();
  result.err = child.err();
  return result;
}

} // namespace geotandem::testing
