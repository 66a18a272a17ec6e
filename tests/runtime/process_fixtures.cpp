// Real processes for the runtime's tests (process_fixtures.hpp).
#include "process_fixtures.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "geotandem/store/store.hpp"
#include "test_paths.hpp"

extern char** environ;

namespace geotandem::testing {

pid_t spawn_logged(std::vector<std::string> argv, const std::string& log_path) {
  std::vector<char*> raw;
  for (auto& a : argv)
    raw.push_back(a.data());
  raw.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, raw[0], &actions, nullptr, raw.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start " + argv[0]);
  return pid;
}

pid_t spawn_geotandem(const std::vector<std::string>& args, const std::string& log_path) {
  std::vector<std::string> argv{test_paths::binary()};
  argv.insert(argv.end(), args.begin(), args.end());
  return spawn_logged(std::move(argv), log_path);
}

int wait_exit(pid_t pid, double timeout_s) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  for (;;) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (std::chrono::steady_clock::now() > until) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

namespace {
// Fields of /proc/PID/stat after the command name: state, ppid.
bool stat_of(pid_t pid, char& state, pid_t& ppid) {
  std::string text;
  try { // a process that exits while its stat is read fails the read (ESRCH): it is gone
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    text.assign(std::istreambuf_iterator<char>(in), {});
  } catch (const std::exception&) {
    return false;
  }
  const auto close = text.rfind(')');
  if (close == std::string::npos) return false;
  std::istringstream rest(text.substr(close + 2));
  rest >> state >> ppid;
  return bool(rest);
}
} // namespace

std::vector<pid_t> children_of(pid_t parent) {
  std::vector<pid_t> out;
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    char state = 0;
    pid_t ppid = 0;
    const pid_t pid = std::stoi(name);
    if (stat_of(pid, state, ppid) && ppid == parent && state != 'Z') out.push_back(pid);
  }
  return out;
}

bool alive(pid_t pid) {
  char state = 0;
  pid_t ppid = 0;
  return stat_of(pid, state, ppid) && state != 'Z';
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

std::map<std::uint64_t, StoredComponent> components_of(const std::string& store_dir, bool check_meshes) {
  const auto store = store::ComponentStore::open(store_dir);
  std::map<std::uint64_t, StoredComponent> out;
  for (const store::ComponentRow& row : store.query()) {
    StoredComponent c{row.stats.volume, row.stats.closed, row.stats.cut_by_border, false};
    if (check_meshes) {
      const mesh::SurfaceMesh m = store.read(row);
      std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
      for (const auto& t : m.triangles)
        for (int i = 0; i < 3; ++i) {
          auto a = t[static_cast<std::size_t>(i)], b = t[static_cast<std::size_t>((i + 1) % 3)];
          ++edges[{std::min(a, b), std::max(a, b)}];
        }
      c.manifold = !edges.empty();
      for (const auto& [e, n] : edges)
        c.manifold = c.manifold && n == 2;
    }
    if (!out.emplace(row.key, c).second) throw std::runtime_error("key twice in the index");
  }
  return out;
}

} // namespace geotandem::testing
