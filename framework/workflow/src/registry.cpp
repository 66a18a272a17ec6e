#include "geotandem/workflow/registry.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <filesystem>

#include "geotandem/core/error.hpp"
#include "geotandem/workflow/suggest.hpp"
#include "library_check.hpp"

namespace fs = std::filesystem;

namespace geotandem::workflow {

PluginRegistry::~PluginRegistry() {
  // Libraries are deliberately never dlclose()d: descriptors, parameter specs and callbacks live in
  // them, and volumes made by a plugin may outlive the registry (shared_ptr). Unloading at exit
  // also races with the plugin's own static destructors. The OS reclaims them at process exit.
  plugins_.clear();
}

void PluginRegistry::add(std::shared_ptr<Plugin> plugin) {
  if (const Plugin* existing = find(plugin->name()))
    throw InvalidArgument("two plugins are named '" + plugin->name() + "': " + existing->origin() + " and " +
                              plugin->origin(),
                          {}, "remove one from the plugin search path");
  plugins_.push_back(std::move(plugin));
}

void PluginRegistry::load_library(const std::string& path) {
  detail::check_plugin_library(path); // before dlopen(), which hangs on a FIFO and SIGBUSes on a truncated copy
  ::dlerror();
  void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = ::dlerror();
    throw FormatError(std::string("cannot load plugin library: ") + (why ? why : "unknown reason"), {path},
                      "check that it was built for this machine and that its dependencies are installed");
  }
  handles_.push_back(handle);
  void* symbol = ::dlsym(handle, GEOTANDEM_PLUGIN_ENTRY_NAME);
  if (!symbol)
    throw FormatError(std::string("the library has no entry point '") + GEOTANDEM_PLUGIN_ENTRY_NAME + "'", {path},
                      "define it with GEOTANDEM_PLUGIN_EXPORT (see docs/plugins.md)");
  auto entry = reinterpret_cast<gt_plugin_entry_fn>(symbol);
  add(plugin_from_descriptor(entry(), path));
}

void PluginRegistry::discover(const std::string& search_path, Logger& log) {
  std::size_t start = 0;
  while (start <= search_path.size()) {
    std::size_t colon = search_path.find(':', start);
    std::string dir = search_path.substr(start, colon == std::string::npos ? std::string::npos : colon - start);
    start = colon == std::string::npos ? search_path.size() + 1 : colon + 1;
    std::error_code ec;
    if (dir.empty() || !fs::is_directory(dir, ec)) continue;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      auto name = entry.path().filename().string();
      if (name.rfind("geotandem_", 0) == 0 && entry.path().extension() == ".so") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end()); // a predictable order, whatever the filesystem returns
    for (const auto& file : files) {
      try {
        load_library(file.string());
        log.debug("loaded plugin library " + file.string());
      } catch (const Error& e) {
        failures_.emplace_back(file.string(), e.what());
        log.warning(std::string("skipping plugin: ") + e.what());
      }
    }
  }
}

std::string PluginRegistry::default_search_path() {
  std::string path;
  if (const char* env = std::getenv("GEOTANDEM_PLUGIN_PATH")) path = env;
  char self[PATH_MAX] = {0};
  ssize_t n = ::readlink("/proc/self/exe", self, sizeof self - 1);
  if (n > 0) {
    fs::path prefix = fs::path(std::string(self, static_cast<std::size_t>(n))).parent_path().parent_path();
    path += (path.empty() ? "" : ":") + (prefix / "lib" / "geotandem" / "plugins").string();
  }
  return path;
}

const Plugin* PluginRegistry::find(const std::string& name) const {
  for (const auto& p : plugins_)
    if (p->name() == name) return p.get();
  return nullptr;
}

const Plugin& PluginRegistry::get(const std::string& name) const {
  if (const Plugin* p = find(name)) return *p;
  std::vector<std::string> names;
  for (const auto& p : plugins_)
    names.push_back(p->name());
  std::string hint = suggestion_hint(name, names);
  for (const auto& [file, reason] : failures_)
    if (fs::path(file).stem().string() == "geotandem_" + name) hint += "; " + file + " failed to load: " + reason;
  throw InvalidArgument("unknown plugin '" + name + "'", {}, hint);
}

std::vector<const Plugin*> PluginRegistry::list() const {
  std::vector<const Plugin*> out;
  for (const auto& p : plugins_)
    out.push_back(p.get());
  std::sort(out.begin(), out.end(), [](const Plugin* a, const Plugin* b) { return a->name() < b->name(); });
  return out;
}

} // namespace geotandem::workflow
