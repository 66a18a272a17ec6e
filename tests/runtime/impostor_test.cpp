// A stranger on the same machine cannot join a run (issue 52): `geotandem extract --workers 2` on
// the default loopback address while runtime_impostor (impostor.cpp; the user nobody when the
// tests run as root) reads each worker's token and the manager's port from /proc, races the real
// worker to connect under that token and under the tokens of the replacements to come, and
// answers every task with a forged DONE. The run must end by itself, with exit 0 and the
// components of the in-process extraction, key for key; the impostor must have seen the tokens
// (the test is not vacuous) and never have been given a task.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "process_fixtures.hpp"
#include "scratch.hpp"

namespace geotandem::testing {
namespace {

// The impostor is built beside this test.
std::string impostor_path() {
  return (std::filesystem::read_symlink("/proc/self/exe").parent_path() / "runtime_impostor").string();
}

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
    ++n;
  return n;
}

TEST(Strangers, AnImpostorWithTheWorkersTokensCannotJoinChangeOrHangARun) {
  ScratchDir dir;
  const std::string cube = dir.file("cube.raw");
  auto r = run_geotandem("-q synth --kind analytic --shape 48 44 40 --seed 3 --out '" + cube + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_geotandem("-q extract '" + cube + "' --iso 0.5 --block-size 8 --workers 0 --out '" + dir.file("ref") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto reference = components_of(dir.file("ref"), false);
  ASSERT_GT(reference.size(), 5u);
  // How long a clean run takes here: a run with the impostor may take a few times that (refused
  // handshakes), never minutes. On a run a stranger could join, it hung for good.
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t clean = spawn_geotandem(
      {"-q", "extract", cube, "--iso", "0.5", "--block-size", "8", "--workers", "2", "--out", dir.file("clean")},
      dir.file("clean.log"));
  ASSERT_EQ(wait_exit(clean, 300), 0) << read_text(dir.file("clean.log"));
  const double clean_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(components_of(dir.file("clean"), false).size(), reference.size());

  std::size_t tokens_seen = 0;
  for (int round = 0; round < 3; ++round) {
    const std::string out = dir.file("run" + std::to_string(round)), log = out + ".log";
    const pid_t manager = spawn_geotandem(
        {"--log-level", "info", "extract", cube, "--iso", "0.5", "--block-size", "8", "--workers", "2", "--out", out},
        log);
    const pid_t impostor = spawn_logged({impostor_path(), std::to_string(manager), "600"}, out + ".impostor");
    const double bound = 60 + 20 * clean_s;
    const int code = wait_exit(manager, bound);
    kill(impostor, SIGTERM);
    wait_exit(impostor, 10);
    const std::string text = read_text(log), seen = read_text(out + ".impostor");
    ASSERT_NE(code, -1) << "the run hung (killed after " << bound << " s):\n" << text << "\nimpostor:\n" << seen;
    ASSERT_EQ(code, 0) << text << "\nimpostor:\n" << seen;
    EXPECT_EQ(seen.find("got "), std::string::npos) << "the impostor was answered:\n" << seen << "\n" << text;
    EXPECT_EQ(text.find("second HELLO"), std::string::npos) << text;
    tokens_seen += count_of(seen, "saw worker ");
    if (seen.find("saw worker ") != std::string::npos) {
      EXPECT_NE(text.find("refused a worker connection"), std::string::npos) << text << "\nimpostor:\n" << seen;
    }
    // The same components, key for key, as the in-process run.
    const auto got = components_of(out, round == 0);
    ASSERT_EQ(got.size(), reference.size()) << text;
    for (const auto& [key, c] : reference) {
      ASSERT_TRUE(got.count(key)) << "component " << key << " missing:\n" << text;
      EXPECT_NEAR(got.at(key).volume, c.volume, 0.005 * std::abs(c.volume) + 1e-9) << key;
    }
  }
  EXPECT_GE(tokens_seen, 3u) << "the impostor should read the workers' tokens in /proc in most rounds";
}

} // namespace
} // namespace geotandem::testing
