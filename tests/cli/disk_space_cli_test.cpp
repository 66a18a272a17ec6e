// A cube the disk cannot hold is refused before anything is written: `geotandem synth` onto a full
// file system, and a recipe whose attribute cube would not fit, at validation. The small disk is a
// real 1 MiB tmpfs mounted in a private mount namespace (unshare -m), so it needs root.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "scratch.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;
using geotandem::testing::CommandResult;
using geotandem::testing::ScratchDir;

namespace {

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Runs `geotandem ARGS` with a 1 MiB tmpfs mounted on `small` (which must exist), in a mount
// namespace of its own: the mount vanishes with the command.
CommandResult run_on_small_disk(const fs::path& small, const std::string& args) {
  const fs::path out = small.parent_path() / "small.out", err = small.parent_path() / "small.err";
  const std::string script =
      "mount -t tmpfs -o size=1m tmpfs '" + small.string() + "' && \"" + test_paths::binary() + "\" " + args;
  const std::string command =
      "unshare -m sh -c \"$GEOTANDEM_DISK_SCRIPT\" >'" + out.string() + "' 2>'" + err.string() + "' </dev/null";
  ::setenv("GEOTANDEM_DISK_SCRIPT", script.c_str(), 1);
  const int status = std::system(command.c_str());
  ::unsetenv("GEOTANDEM_DISK_SCRIPT");
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

bool can_mount() {
  return ::geteuid() == 0 && std::system("unshare -m true >/dev/null 2>&1") == 0;
}

} // namespace

TEST(DiskSpaceCli, ACubeTheDiskCannotHoldIsRefusedBeforeWriting) {
  if (!can_mount()) GTEST_SKIP() << "mounting a small tmpfs needs root and unshare -m";
  ScratchDir dir;
  const fs::path small = dir.path() / "small";
  fs::create_directories(small);
  // 64 x 64 x 64 float32 samples are 1 MiB of samples alone, more than the tmpfs holds with headers.
  auto big = run_on_small_disk(small, "synth --kind analytic --shape 64 64 96 --out '" + (small / "c.raw").string() +
                                          "'; rc=$?; ls -A '" + small.string() + "'; exit $rc");
  EXPECT_EQ(big.exit_code, 3) << big.err;
  EXPECT_NE(big.err.find("1.5 MiB of float32 samples on disk"), std::string::npos) << big.err;
  EXPECT_NE(big.err.find("free"), std::string::npos) << big.err;
  EXPECT_EQ(big.out, "") << "nothing may be left on the full disk";
  // The same command with a cube that fits writes it (the check does not refuse what fits).
  auto fits = run_on_small_disk(small, "synth --kind analytic --shape 40 40 40 --out '" + (small / "c.raw").string() +
                                           "' && ls '" + small.string() + "'");
  EXPECT_EQ(fits.exit_code, 0) << fits.err;
  EXPECT_NE(fits.out.find("c.raw"), std::string::npos) << fits.out;
}

TEST(DiskSpaceCli, ARecipeWhoseAttributeCubeCannotFitFailsValidationAtItsLine) {
  if (!can_mount()) GTEST_SKIP() << "mounting a small tmpfs needs root and unshare -m";
  ScratchDir dir;
  const fs::path small = dir.path() / "small";
  fs::create_directories(small);
  const fs::path recipe = dir.path() / "r.yaml";
  std::ofstream(recipe) << "version: 1\ninput:\n  synthetic: {kind: analytic, shape: [64, 64, 96]}\nsteps:\n"
                           "  - step: extract\n    iso: 0.5\noutput:\n  directory: "
                        << small.string() << "\n  attribute: attribute.raw\n";
  auto r = run_on_small_disk(small, "validate '" + recipe.string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("r.yaml:9:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("output.attribute needs 1.5 MiB"), std::string::npos) << r.err;
  // Without the attribute cube the same recipe is valid on the same disk.
  std::ofstream(recipe) << "version: 1\ninput:\n  synthetic: {kind: analytic, shape: [64, 64, 96]}\nsteps:\n"
                           "  - step: extract\n    iso: 0.5\noutput:\n  directory: "
                        << small.string() << "\n";
  auto ok = run_on_small_disk(small, "validate '" + recipe.string() + "'");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}
