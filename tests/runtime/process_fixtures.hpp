#pragma once
// Real processes for the runtime's tests: the geotandem executable started in the background,
// its children (the workers) found through /proc, and stores compared component by component.
#include <sys/types.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace geotandem::testing {

// Starts `argv` (argv[0] found on PATH unless it holds a slash) in the background with
// posix_spawn, its stdout and stderr to `log_path`. Throws when it cannot be started.
pid_t spawn_logged(std::vector<std::string> argv, const std::string& log_path);
// `geotandem ARGS...` through spawn_logged.
pid_t spawn_geotandem(const std::vector<std::string>& args, const std::string& log_path);
// Waits for the process; its exit code, 128 + signal when killed, -1 after `timeout_s` (then it is
// SIGKILLed).
int wait_exit(pid_t pid, double timeout_s);
// The live (not zombie) children of `parent`.
std::vector<pid_t> children_of(pid_t parent);
// True while the process exists and is not a zombie.
bool alive(pid_t pid);
std::string read_text(const std::string& path);

struct StoredComponent {
  double volume = 0;
  bool closed = false;
  bool cut = false;
  bool manifold = false; // every edge of the stored surface in exactly two triangles
};
// Every component of a store by key; `check_meshes` reads each surface and tests it.
std::map<std::uint64_t, StoredComponent> components_of(const std::string& store_dir, bool check_meshes);

} // namespace geotandem::testing
