#pragma once
// The plugins a run can use. main builds one registry, adds the built-ins by an explicit call,
// then discovers shared-library plugins on the search path. No global state.

#include <memory>
#include <string>
#include <vector>

#include "geotandem/core/log.hpp"
#include "geotandem/workflow/plugin.hpp"

namespace geotandem::workflow {

class PluginRegistry {
public:
  PluginRegistry() = default;
  PluginRegistry(const PluginRegistry&) = delete;
  PluginRegistry& operator=(const PluginRegistry&) = delete;
  PluginRegistry(PluginRegistry&&) = default;
  PluginRegistry& operator=(PluginRegistry&&) = default;
  ~PluginRegistry();

  // Adds a plugin; a second plugin of the same name is an InvalidArgument naming both origins.
  void add(std::shared_ptr<Plugin> plugin);

  // Loads one shared library (file checks, dlopen, entry point, descriptor checks). Throws FormatError
  // naming the file: a FIFO, device or directory, not an ELF shared object of this machine, truncated
  // (checked before dlopen, see src/library_check.hpp), not loadable, no entry point, wrong interface
  // version, bad descriptor; IoError when the file cannot be read.
  void load_library(const std::string& path);

  // Loads every `geotandem_*.so` in each directory of `search_path` (':'-separated). A library
  // that fails to load is reported through `log` as a warning and skipped, so one broken plugin
  // does not stop runs that do not use it; naming it in a recipe then fails with that reason.
  void discover(const std::string& search_path, Logger& log);

  // The search path: $GEOTANDEM_PLUGIN_PATH, then <prefix>/lib/geotandem/plugins next to the
  // running executable.
  static std::string default_search_path();

  const Plugin* find(const std::string& name) const;
  // Like find(), but throws InvalidArgument naming the unknown plugin, the nearest known name and
  // any load failure recorded for it.
  const Plugin& get(const std::string& name) const;
  std::vector<const Plugin*> list() const;

private:
  std::vector<std::shared_ptr<Plugin>> plugins_;
  std::vector<std::pair<std::string, std::string>> failures_; // file, reason
  std::vector<void*> handles_;                                // dlopen handles, never closed (see .cpp)
};

} // namespace geotandem::workflow
