// The plugin search path holding what is not a plugin library (issue 52, item 5): a FIFO named like a
// plugin hung `validate`, `plugins` and `run-workflow` in dlopen(); a truncated copy of a real plugin
// killed them with SIGBUS. Each command now finishes, names the file and says why it skipped it, and
// the real plugin beside them still loads.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "child_process.hpp"
#include "scratch.hpp"
#include "test_paths.hpp"

namespace geotandem {
namespace {

namespace fs = std::filesystem;
using testing::run_child;
using testing::ScratchDir;

// GEOTANDEM_PLUGIN_PATH for the children this test starts (they inherit the environment), restored
// when the test ends.
class PluginPath {
public:
  explicit PluginPath(const std::string& dir) {
    if (const char* old = std::getenv("GEOTANDEM_PLUGIN_PATH")) old_ = old;
    ::setenv("GEOTANDEM_PLUGIN_PATH", dir.c_str(), 1);
  }
  ~PluginPath() {
    if (old_.empty())
      ::unsetenv("GEOTANDEM_PLUGIN_PATH");
    else
      ::setenv("GEOTANDEM_PLUGIN_PATH", old_.c_str(), 1);
  }

private:
  std::string old_;
};

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The first `bytes` bytes of `from`, as an interrupted copy leaves them.
void copy_head(const std::string& from, const std::string& to, std::uintmax_t bytes) {
  std::ifstream in(from, std::ios::binary);
  std::string head(bytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(bytes));
  ASSERT_EQ(static_cast<std::uintmax_t>(in.gcount()), bytes);
  write_text(to, head);
}

struct PluginDir {
  ScratchDir dir;
  std::string plugins, fifo, truncated, folder;
  PluginDir() {
    plugins = dir.file("plugins");
    fs::create_directories(plugins);
    // A real plugin the build makes (tests/workflow/plugins/test_plugins.c), whole: it must still load.
    const std::string real = test_paths::plugins() + "/boxsum/geotandem_boxsum.so";
    fs::copy_file(real, plugins + "/geotandem_boxsum.so");
    fifo = plugins + "/geotandem_fifo.so";
    EXPECT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
    // Half of the same library: its ELF and program headers are whole, its later segments are not.
    truncated = plugins + "/geotandem_truncated.so";
    copy_head(real, truncated, fs::file_size(real) / 2);
    folder = plugins + "/geotandem_folder.so";
    fs::create_directories(folder);
  }
};

// Every skipped entry is named, with its reason, in a warning; nothing ended by a signal.
void expect_skipped_with_reasons(const testing::ChildResult& r, const PluginDir& p, const std::string& what) {
  ASSERT_FALSE(r.hung) << what << " hung on the plugin path";
  EXPECT_LT(r.exit_code, 128) << what << " died of a signal: " << r.err;
  for (const auto& [file, reason] :
       {std::pair{p.fifo, "FIFO"}, std::pair{p.truncated, "truncated"}, std::pair{p.folder, "a directory"}}) {
    const auto at = r.err.find("skipping plugin: " + file);
    ASSERT_NE(at, std::string::npos) << what << " does not name " << file << ": " << r.err;
    const auto line_end = r.err.find('\n', at);
    EXPECT_NE(r.err.substr(at, line_end - at).find(reason), std::string::npos)
        << what << " does not say why " << file << " was skipped: " << r.err;
  }
}

std::string recipe(const std::string& out, const std::string& extra_step = {}) {
  return "version: 1\ninput:\n  synthetic: {kind: analytic, shape: [40, 40, 40]}\nsteps:\n"
         "  - step: boxsum\n    input: input\n" +
         extra_step + "  - step: extract\n    iso: 0.5\noutput:\n  directory: " + out + "\n";
}

TEST(PluginPathCli, FifosDirectoriesAndTruncatedLibrariesAreSkippedWithAWarningNamingThem) {
  PluginDir p;
  PluginPath path(p.plugins);
  const std::string scratch = p.dir.path().string();
  write_text(p.dir.file("r.yaml"), recipe(p.dir.file("out")));

  auto listed = run_child(scratch, {"plugins"}, 60);
  expect_skipped_with_reasons(listed, p, "plugins");
  EXPECT_EQ(listed.exit_code, 0) << listed.err;
  EXPECT_NE(listed.out.find("boxsum"), std::string::npos) << "the whole library beside them loads: " << listed.out;

  auto valid = run_child(scratch, {"validate", p.dir.file("r.yaml")}, 60);
  expect_skipped_with_reasons(valid, p, "validate");
  EXPECT_EQ(valid.exit_code, 0) << valid.err;

  auto ran = run_child(scratch, {"-q", "run-workflow", p.dir.file("r.yaml")}, 120);
  expect_skipped_with_reasons(ran, p, "run-workflow");
  EXPECT_EQ(ran.exit_code, 0) << ran.err;
  EXPECT_TRUE(fs::exists(p.dir.file("out/report.html")));
}

TEST(PluginPathCli, NamingASkippedLibraryInARecipeSaysWhyItDidNotLoad) {
  PluginDir p;
  // The truncated library alone (dlopen() of it died of SIGBUS, exit 4).
  fs::remove(p.fifo);
  fs::remove(p.folder);
  PluginPath path(p.plugins);
  write_text(p.dir.file("r.yaml"), recipe(p.dir.file("out"), "  - step: truncated\n"));
  auto r = run_child(p.dir.path().string(), {"validate", p.dir.file("r.yaml")}, 60);
  ASSERT_FALSE(r.hung);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const auto at = r.err.find("error:");
  ASSERT_NE(at, std::string::npos) << r.err;
  const std::string error = r.err.substr(at);
  EXPECT_NE(error.find("'truncated'"), std::string::npos) << error;
  EXPECT_NE(error.find(p.truncated + " failed to load"), std::string::npos) << error;
  EXPECT_NE(error.find("beyond the end of the file"), std::string::npos) << error;
}

} // namespace
} // namespace geotandem
