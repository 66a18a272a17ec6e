// Hostile but realistic invocations: FIFOs, devices and directories where files belong, recipes with
// duplicate keys or a second document, absurd shapes, a cube one sample thick, overflowing sidecars, a negative SEG-Y
// sample interval, unwritable outputs, out of memory, Ctrl-C and SIGTERM. Each ends promptly with its typed exit code
// (2, 3, 4, 5; 130 for an interrupt), never a hang, never 70.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "scratch.hpp"
#include "test_paths.hpp"

namespace geotandem {
namespace {

using testing::run_child;
using testing::run_geotandem;
using testing::ScratchDir;

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string extract_recipe(const std::string& input_line, const std::string& out_dir) {
  return "version: 1\ninput:\n  " + input_line + "\nsteps:\n  - step: extract\n    input: input\n    iso: 0.5\n" +
         "output:\n  directory: " + out_dir + "\n";
}

TEST(HostileInputCli, FifosDevicesAndDirectoriesAreRefusedAtOnce) {
  ScratchDir dir;
  const auto fifo = dir.file("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  std::filesystem::create_directories(dir.file("folder"));
  // A raw cube whose sidecar is a FIFO.
  write_text(dir.file("cube.raw"), std::string(4096, '\0'));
  ASSERT_EQ(::mkfifo((dir.file("cube.raw") + ".json").c_str(), 0644), 0);
  struct Case {
    std::vector<std::string> args;
    int code;
    std::string names;
  };
  const std::vector<Case> cases = {
      {{"info", fifo}, 3, "FIFO"},
      {{"extract", fifo, "--iso", "0.5", "--out", dir.file("s")}, 3, "FIFO"},
      {{"validate", fifo}, 2, "not a regular file"},
      {{"run-workflow", fifo}, 2, "not a regular file"},
      {{"info", dir.file("cube.raw")}, 3, "sidecar is not a regular file"},
      {{"validate", "/dev/zero"}, 2, "not a regular file"},
      {{"validate", "/dev/urandom"}, 2, "not a regular file"},
      {{"validate", dir.file("folder")}, 2, "is a directory"},
      {{"run-workflow", dir.file("folder")}, 2, "is a directory"},
  };
  for (const auto& c : cases) {
    auto r = run_child(dir.path().string(), c.args, 60);
    ASSERT_FALSE(r.hung) << c.args[0] << " " << c.args[1] << " hung";
    EXPECT_EQ(r.exit_code, c.code) << c.args[0] << " " << c.args[1] << ": " << r.err;
    EXPECT_NE(r.err.find(c.names), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.args[1]), std::string::npos) << "names the path: " << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("s")));
}

TEST(HostileInputCli, OversizedRecipesAreRefused) {
  ScratchDir dir;
  write_text(dir.file("huge.yaml"), "version: 1\n# " + std::string(2 << 20, 'x') + "\n");
  auto r = run_child(dir.path().string(), {"validate", dir.file("huge.yaml")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("limited to"), std::string::npos) << r.err;
}

TEST(HostileInputCli, RecipeDuplicateKeysSecondDocumentsAndControlCharactersAreErrors) {
  ScratchDir dir;
  write_text(dir.file("dup.yaml"), "version: 1\ninput:\n  synthetic: {kind: analytic}\nsteps:\n  - step: extract\n"
                                   "    input: input\n    iso: 0.5\n    iso: 0.9\n");
  auto dup = run_geotandem("validate '" + dir.file("dup.yaml") + "'");
  EXPECT_EQ(dup.exit_code, 2) << dup.err;
  EXPECT_NE(dup.err.find("key 'iso' is given twice (lines 7 and 8)"), std::string::npos) << dup.err;
  EXPECT_NE(dup.err.find("dup.yaml:8:"), std::string::npos) << dup.err;

  write_text(dir.file("two.yaml"), extract_recipe("synthetic: {kind: analytic}", "o") + "---\nversion: 1\n");
  auto two = run_geotandem("validate '" + dir.file("two.yaml") + "'");
  EXPECT_EQ(two.exit_code, 2) << two.err;
  EXPECT_NE(two.err.find("second YAML document"), std::string::npos) << two.err;

  write_text(dir.file("ctl.yaml"), extract_recipe("file: \"cube\\x01.raw\"", "o"));
  auto ctl = run_geotandem("validate '" + dir.file("ctl.yaml") + "'");
  EXPECT_EQ(ctl.exit_code, 2) << ctl.err;
  EXPECT_NE(ctl.err.find("control character 0x01"), std::string::npos) << ctl.err;

  // Aliases that refer to themselves, or expand exponentially, end with an error, not a stack overflow.
  write_text(dir.file("cycle.yaml"), "version: 1\ninput: &a {synthetic: *a}\n");
  auto cycle = run_child(dir.path().string(), {"validate", dir.file("cycle.yaml")}, 60);
  EXPECT_EQ(cycle.exit_code, 2) << cycle.err;
  EXPECT_NE(cycle.err.find("nests deeper"), std::string::npos) << cycle.err;
  std::string bomb = "a: &a [1,1,1,1,1,1,1,1,1,1]\n";
  for (char c = 'b'; c <= 'h'; ++c) {
    bomb += std::string(1, c) + ": &" + c + " [";
    for (int n = 0; n < 10; ++n)
      bomb += std::string(n ? "," : "") + "*" + static_cast<char>(c - 1);
    bomb += "]\n";
  }
  write_text(dir.file("bomb.yaml"), bomb);
  auto expanded = run_child(dir.path().string(), {"validate", dir.file("bomb.yaml")}, 60);
  EXPECT_FALSE(expanded.hung);
  EXPECT_EQ(expanded.exit_code, 2) << expanded.err;

  // Found by fuzz_recipe: YAML::LoadAll never ended on this malformed recipe (and ate the memory).
  // The address-space limit keeps a regression from eating the machine; a sanitizer's runtime
  // cannot start under it, and there the deadline alone catches the loop.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  const unsigned long looped_limit = 0;
#else
  const unsigned long looped_limit = 2UL << 30;
#endif
  auto looped = run_child(dir.path().string(),
                          {"validate", test_paths::source() + "/tests/fuzz/regressions/recipe_loadall_loop.yaml"}, 60,
                          looped_limit);
  EXPECT_FALSE(looped.hung);
  EXPECT_EQ(looped.exit_code, 2) << looped.err;

  write_text(dir.file("nul.yaml"), std::string("version: 1\ninput:\n  file: a\0b.raw\n", 31));
  auto nul = run_geotandem("validate '" + dir.file("nul.yaml") + "'");
  EXPECT_EQ(nul.exit_code, 2) << nul.err;
  EXPECT_NE(nul.err.find("NUL"), std::string::npos) << nul.err;
}

TEST(HostileInputCli, AMalformedSetValueIsNamedAsTheSet) {
  ScratchDir dir;
  write_text(dir.file("ok.yaml"), extract_recipe("synthetic: {kind: analytic}", "o"));
  auto r = run_geotandem("validate '" + dir.file("ok.yaml") + "' --set 'steps.extract.iso=[1,'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--set steps.extract.iso=[1,"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("ok.yaml:1:1"), std::string::npos) << r.err;
}

TEST(HostileInputCli, AnUnwritableOutputDirectoryIsAnIoError) {
  ScratchDir dir;
  write_text(dir.file("blocker"), "a file where the output directory's parent should be");
  write_text(dir.file("w.yaml"),
             extract_recipe("synthetic: {kind: analytic, shape: [40, 40, 40]}", dir.file("blocker") + "/out"));
  auto r = run_geotandem("-q run-workflow '" + dir.file("w.yaml") + "'");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("blocker"), std::string::npos) << r.err;
}

TEST(HostileInputCli, AShapeTheMachineCannotHoldFailsValidationWithTheNumbers) {
  ScratchDir dir;
  write_text(dir.file("big.yaml"), extract_recipe("synthetic: {kind: analytic, shape: [100000, 100000, 100000]}", "o"));
  // The oracle: two 100000 x 100000 float32 slices need 80 GB.
  std::ifstream meminfo("/proc/meminfo");
  std::string label;
  unsigned long long kib = 0;
  meminfo >> label >> kib;
  if (kib * 1024ULL >= 80000000000ULL) GTEST_SKIP() << "this machine holds two such slices";
  auto r = run_child(dir.path().string(), {"validate", dir.file("big.yaml")}, 60);
  ASSERT_FALSE(r.hung);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("74.5 GiB of memory"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("this machine has"), std::string::npos) << r.err;
  auto synth =
      run_child(dir.path().string(), {"synth", "--shape", "100000", "100000", "40", "--out", dir.file("big.raw")}, 60);
  ASSERT_FALSE(synth.hung);
  EXPECT_EQ(synth.exit_code, 2) << synth.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("big.raw")));
}

TEST(HostileInputCli, ARawSidecarWhoseByteCountOverflowsIsRefused) {
  ScratchDir dir;
  const auto cube = dir.file("c.raw");
  ASSERT_EQ(run_geotandem("-q synth --kind analytic --shape 40 40 40 --out '" + cube + "'").exit_code, 0);
  auto sidecar = nlohmann::json::parse(std::ifstream(cube + ".json"));
  sidecar["shape"] = {4294967296LL, 4294967296LL, 1024};
  write_text(cube + ".json", sidecar.dump(2));
  auto r = run_geotandem("info '" + cube + "'");
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_NE(r.err.find("more than 2^64 bytes"), std::string::npos) << r.err;
}

TEST(HostileInputCli, NegativeCountsAndNaNBoundsAreUsageErrors) {
  // CLI11 turns "-1" for an unsigned option into 2^64 - 1: `--workers -1` started local workers
  // until the machine ran out of processes, `--limit -1` listed everything, and a NaN volume bound
  // silently selected nothing.
  ScratchDir dir;
  const auto cube = dir.file("c.raw");
  ASSERT_EQ(run_geotandem("-q synth --kind analytic --shape 40 40 40 --out '" + cube + "'").exit_code, 0);
  auto workers = run_child(dir.path().string(),
                           {"-q", "extract", cube, "--iso", "0.5", "--out", dir.file("st"), "--workers", "-1"}, 30);
  ASSERT_FALSE(workers.hung) << "--workers -1 started workers";
  EXPECT_EQ(workers.exit_code, 2) << workers.err;
  EXPECT_NE(workers.err.find("--workers"), std::string::npos) << workers.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("st")));

  ASSERT_EQ(run_geotandem("-q extract '" + cube + "' --iso 0.5 --workers 0 --out '" + dir.file("st") + "'").exit_code,
            0);
  const std::string store = " '" + dir.file("st") + "'";
  const auto listed = run_geotandem("-q store ls" + store);
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  for (const std::string option : {"--min-triangles -3", "--max-vertices -1", "--limit -1"}) {
    auto r = run_geotandem("-q store ls" + store + " " + option);
    EXPECT_EQ(r.exit_code, 2) << option << ": " << r.out;
    EXPECT_NE(r.err.find("is negative"), std::string::npos) << option << ": " << r.err;
  }
  for (const std::string option : {"--min-volume nan", "--max-volume NaN"}) {
    auto r = run_geotandem("-q store ls" + store + " " + option);
    EXPECT_EQ(r.exit_code, 2) << option << ": " << r.out;
    EXPECT_NE(r.err.find("is not a number"), std::string::npos) << option << ": " << r.err;
  }
  // Infinite bounds are bounds that are not there.
  auto unbounded = run_geotandem("-q store ls" + store + " --min-volume -inf --max-volume inf");
  EXPECT_EQ(unbounded.exit_code, 0) << unbounded.err;
  EXPECT_EQ(unbounded.out, listed.out);

  auto seed = run_geotandem("-q synth --kind analytic --shape 40 40 40 --seed -1 --out '" + dir.file("s.raw") + "'");
  EXPECT_EQ(seed.exit_code, 2) << seed.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("s.raw")));
  auto timeout =
      run_child(dir.path().string(),
                {"worker", "--connect", "tcp://127.0.0.1:9", "--token", "t", "--manager-timeout", "nan"}, 30);
  ASSERT_FALSE(timeout.hung);
  EXPECT_EQ(timeout.exit_code, 2) << timeout.err;
}

TEST(HostileInputCli, ACubeOneSampleThickIsRefusedBeforeAStoreIsMade) {
  // A single crossline (20 x 1 x 30 samples) of a raw cube written by hand: a 2-D section, no cell.
  ScratchDir dir;
  const auto cube = dir.file("section.raw");
  std::string samples(20 * 1 * 30 * sizeof(float), '\0');
  for (std::size_t i = 0; i < samples.size() / sizeof(float); ++i) {
    const float v = i % 7 == 0 ? 1.0f : 0.0f;
    std::memcpy(samples.data() + i * sizeof(float), &v, sizeof v);
  }
  write_text(cube, samples);
  nlohmann::json sidecar = {{"format", "geotandem-raw"},
                            {"version", 1},
                            {"dtype", "float32"},
                            {"byte_order", "little"},
                            {"order", "C"},
                            {"shape", {20, 1, 30}},
                            {"axes", {"inline", "crossline", "sample"}}};
  sidecar["geometry"] = {
      {"inline0", 1},    {"inline_step", 1},
      {"crossline0", 1}, {"crossline_step", 1},
      {"z0", 0},         {"dz", 4},
      {"z_unit", "ms"},  {"affine", {{"x0", 0.0}, {"xi", 12.5}, {"xj", 0.0}, {"y0", 0.0}, {"yi", 0.0}, {"yj", 12.5}}}};
  write_text(cube + ".json", sidecar.dump());
  const auto info = run_geotandem("-q info '" + cube + "'");
  ASSERT_EQ(info.exit_code, 0) << info.err; // a valid cube, just not 3-D

  for (const std::string blocks : {"0", "8"}) {
    auto r =
        run_geotandem("-q extract '" + cube + "' --iso 0.5 --block-size " + blocks + " --out '" + dir.file("st") + "'");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("section.raw: the cube has 1 sample along the crossline axis"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("at least 2 samples along each axis"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("st"))) << "a store was made for a cube it cannot hold";
  }
  write_text(dir.file("r.yaml"), extract_recipe("file: section.raw", "out"));
  auto r = run_geotandem("-q run-workflow '" + dir.file("r.yaml") + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("section.raw: the cube has 1 sample along the crossline axis"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out/store")));
}

TEST(HostileInputCli, ANegativeSegySampleIntervalIsAnError) {
  ScratchDir dir;
  const auto cube = dir.file("c.segy");
  ASSERT_EQ(run_geotandem("-q synth --kind analytic --shape 40 40 40 --out '" + cube + "'").exit_code, 0);
  {
    // Binary header bytes 3217-3218: -4000 microseconds as a big-endian signed 16-bit integer.
    std::fstream f(cube, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(3216);
    const char bytes[2] = {static_cast<char>(0xF0), static_cast<char>(0x60)};
    f.write(bytes, 2);
  }
  auto r = run_geotandem("info '" + cube + "'");
  EXPECT_EQ(r.exit_code, 4) << r.out << r.err;
  EXPECT_NE(r.err.find("sample interval is negative (-4000"), std::string::npos) << r.err;
}

TEST(HostileInputCli, OutOfMemorySaysSoAndHowMuch) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "a sanitizer's runtime cannot start under an address-space limit";
#endif
  ScratchDir dir;
  // A cube whose slices need about 1.6 GB each, under a 1 GiB address-space limit. Laying out its
  // bodies (16 G samples' worth) comes first and took 260 s of a slow machine beside other work:
  // the deadline is for a hang, not a measure.
  write_text(dir.file("w.yaml"),
             extract_recipe("synthetic: {kind: analytic, shape: [40, 20000, 20000]}", dir.file("o")) + "");
  auto r = run_child(dir.path().string(), {"-q", "run-workflow", dir.file("w.yaml"), "--set", "steps.extract.axis=k"},
                     1000, 1UL << 30);
  ASSERT_FALSE(r.hung);
  EXPECT_EQ(r.exit_code, 5) << r.err;
  EXPECT_NE(r.err.find("out of memory"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
}

TEST(HostileInputCli, InterruptAndTerminateEndARunningExtractionPromptlyWithAValidStore) {
  ScratchDir dir;
  write_text(dir.file("w.yaml"),
             "version: 1\ninput:\n  synthetic: {kind: seismic, shape: [400, 400, 200]}\nsteps:\n"
             "  - step: envelope\n    input: input\n  - step: extract\n    input: envelope\n    iso: 0.5\n"
             "output:\n  directory: " +
                 dir.file("o") + "\n");
  for (int sig : {SIGINT, SIGTERM}) {
    std::filesystem::remove_all(dir.file("o"));
    testing::Child child(dir.path().string(), {"run-workflow", dir.file("w.yaml")});
    // Wait until the store exists (the extraction has begun), then interrupt.
    for (int n = 0; n < 600 && !std::filesystem::exists(dir.file("o/store/store.json")); ++n)
      ASSERT_FALSE(child.wait_for(0.1)) << "ended before it could be interrupted: " << child.err();
    ASSERT_TRUE(std::filesystem::exists(dir.file("o/store/store.json")));
    child.signal(sig);
    auto code = child.wait_for(20); // "within a second" on an idle machine; generous here
    ASSERT_TRUE(code) << "signal " << sig << " did not end the run";
    EXPECT_TRUE(*code == 130 || *code == 128 + sig) << "signal " << sig << ": exit " << *code << "\n" << child.err();
    auto check = run_geotandem("-q store check '" + dir.file("o/store") + "'");
    EXPECT_EQ(check.exit_code, 0) << "the store is valid after the interrupt: " << check.out << check.err;
  }
}

TEST(HostileInputCli, ASegyFileTruncatedWhileBeingReadIsAClearError) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "the sanitizer's runtime reports SIGBUS itself";
#endif
  ScratchDir dir;
  const auto cube = dir.file("big.segy");
  ASSERT_EQ(run_geotandem("-q synth --kind analytic --shape 300 300 300 --out '" + cube + "'").exit_code, 0);
  const auto full = std::filesystem::file_size(cube);
  testing::Child child(dir.path().string(), {"-q", "extract", cube, "--iso", "0.5", "--out", dir.file("s")});
  // The store appears once the cube is open; cut the file to a page boundary early in its traces.
  for (int n = 0; n < 600 && !std::filesystem::exists(dir.file("s/store.json")); ++n)
    ASSERT_FALSE(child.wait_for(0.05)) << child.err();
  std::filesystem::resize_file(cube, 4096 * 1000);
  auto code = child.wait_for(120);
  ASSERT_TRUE(code) << "hung after the truncation";
  ASSERT_GT(full, 4096u * 1000 * 4) << "the extraction had most of the file still to read";
  EXPECT_EQ(*code, 4) << "a clear error, not a SIGBUS death or a success on a truncated cube: " << child.err();
  EXPECT_EQ(child.err().find("internal error"), std::string::npos) << child.err();
  EXPECT_TRUE(child.err().find("truncated") != std::string::npos || child.err().find("big.segy") != std::string::npos)
      << child.err();
  EXPECT_EQ(run_geotandem("-q store check '" + dir.file("s") + "'").exit_code, 0) << "the store stays valid";
}

} // namespace
} // namespace geotandem
