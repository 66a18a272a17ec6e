// Messages that misled (issue 52, item 7), each through the real executable: SEG-Y sample format
// codes that are no SEG-Y format (a code of 256 was read as a little-endian file and reported as a
// negative sample interval), a required parameter written under another name, an empty --set value,
// and an isovalue beyond the float range (it became "isovalue inf").

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "child_process.hpp"
#include "scratch.hpp"
#include "segy_fixtures.hpp"

namespace geotandem {
namespace {

namespace fs = std::filesystem;
using testing::run_child;
using testing::ScratchDir;

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(MessagesCli, SampleFormatCodesThatAreNoSegyFormatAreNamedAsSuch) {
  ScratchDir dir;
  // The oracle: the same survey with a real format code reads.
  volume::testing::SegySpec spec;
  volume::testing::write_with_segyio(dir.file("good.sgy"), spec);
  auto good = run_child(dir.path().string(), {"-q", "info", "--no-stats", dir.file("good.sgy")}, 60);
  ASSERT_EQ(good.exit_code, 0) << good.err;

  for (int code : {0, 17, 256}) {
    SCOPED_TRACE("format code " + std::to_string(code));
    spec.format = code; // written big-endian by segyio, as the standard says; traces laid out as IEEE
    const std::string cube = dir.file("code" + std::to_string(code) + ".sgy");
    volume::testing::write_with_segyio(cube, spec);
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"info", cube}, {"extract", cube, "--iso", "0.5", "--out", dir.file("s")}}) {
      auto r = run_child(dir.path().string(), args, 60);
      ASSERT_FALSE(r.hung);
      EXPECT_EQ(r.exit_code, 4) << args[0] << ": " << r.err; // a damaged file (README, exit codes)
      EXPECT_NE(r.err.find(cube), std::string::npos) << r.err;
      EXPECT_NE(r.err.find("sample format code " + std::to_string(code) +
                           " (binary header bytes 3225-3226) is not a SEG-Y format code"),
                std::string::npos)
          << r.err;
      EXPECT_EQ(r.err.find("negative"), std::string::npos) << "not an interval's fault: " << r.err;
      EXPECT_EQ(r.err.find("unknown format"), std::string::npos) << "SEG-Y all the same: " << r.err;
    }
  }
  EXPECT_FALSE(fs::exists(dir.file("s")));
}

// The extract step of a recipe whose line 8 is `    isovalue: 0.5` (the key at column 5).
std::string recipe_with(const std::string& iso_line, const std::string& out) {
  return "version: 1\n"
         "input:\n"
         "  synthetic: {kind: analytic, shape: [40, 40, 40]}\n"
         "steps:\n"
         "  - step: envelope\n"
         "    input: input\n"
         "  - step: extract\n" +
         iso_line + "\n" + "output:\n  directory: " + out + "\n";
}

TEST(MessagesCli, ARequiredParameterUnderAnotherNameIsSuggestedWithItsLineAndColumn) {
  ScratchDir dir;
  const std::string path = dir.file("r.yaml");
  write_text(path, recipe_with("    isovalue: 0.5", dir.file("o")));
  auto r = run_child(dir.path().string(), {"validate", path}, 60);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(path + ":8:5:"), std::string::npos) << "the place of 'isovalue': " << r.err;
  EXPECT_NE(r.err.find("needs 'iso'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("did you mean 'iso'?"), std::string::npos) << r.err;

  // Both given: the unknown one is an unknown key, with the same suggestion.
  write_text(path, recipe_with("    iso: 0.5\n    isovalue: 0.5", dir.file("o")));
  r = run_child(dir.path().string(), {"validate", path}, 60);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(path + ":9:5: unknown key 'isovalue'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("did you mean 'iso'?"), std::string::npos) << r.err;
}

TEST(MessagesCli, AnEmptyValueSaysItIsEmptyAndShowsTheExpectedForm) {
  ScratchDir dir;
  const std::string path = dir.file("r.yaml");
  write_text(path, recipe_with("    iso: 0.5", dir.file("o")));
  for (const char* command : {"validate", "run-workflow"}) {
    auto r = run_child(dir.path().string(), {command, path, "--set", "steps.extract.iso="}, 60);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("--set steps.extract.iso=: the value after '=' is empty"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--set steps.extract.iso=VALUE"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("list or mapping"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir.file("o")));
  // The same in the file: `iso:` with nothing after it, placed at the value.
  write_text(path, recipe_with("    iso:", dir.file("o")));
  auto r = run_child(dir.path().string(), {"validate", path}, 60);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("'iso' in step 2 (extract) has no value"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(path + ":8:5:"), std::string::npos) << "the place of the key: " << r.err;
  EXPECT_EQ(r.err.find("list or mapping"), std::string::npos) << r.err;
}

TEST(MessagesCli, AnIsovalueBeyondTheFloatRangeIsRefusedWithTheValueAndTheRange) {
  ScratchDir dir;
  auto synth = run_child(dir.path().string(),
                         {"-q", "synth", "--kind", "analytic", "--shape", "40", "40", "40", "--out", dir.file("c.nc")});
  ASSERT_EQ(synth.exit_code, 0) << synth.err;
  const std::string path = dir.file("r.yaml");
  write_text(path, recipe_with("    iso: 0.5", dir.file("o")));
  const std::string range = "between -3.4028235e+38 and 3.4028235e+38";
  for (const std::string value : {"1e39", "-1e39", "3.5e38"}) {
    SCOPED_TRACE(value);
    auto cli = run_child(dir.path().string(), {"extract", dir.file("c.nc"), "--iso", value, "--out", dir.file("s")});
    EXPECT_EQ(cli.exit_code, 2) << cli.err;
    EXPECT_NE(cli.err.find("parameter 'iso' is " + value + ", beyond the range of a 32-bit float"), std::string::npos)
        << cli.err;
    EXPECT_NE(cli.err.find(range), std::string::npos) << cli.err;
    EXPECT_EQ(cli.err.find("isovalue inf"), std::string::npos) << cli.err;

    auto set = run_child(dir.path().string(), {"validate", path, "--set", "steps.extract.iso=" + value});
    EXPECT_EQ(set.exit_code, 2) << set.err;
    EXPECT_NE(set.err.find("--set steps.extract.iso=" + value), std::string::npos) << set.err;
    EXPECT_NE(set.err.find(range), std::string::npos) << set.err;
  }
  write_text(path, recipe_with("    iso: 1e39", dir.file("o")));
  auto file = run_child(dir.path().string(), {"validate", path});
  EXPECT_EQ(file.exit_code, 2) << file.err;
  EXPECT_NE(file.err.find(path + ":8:10:"), std::string::npos) << file.err;
  EXPECT_NE(file.err.find(range), std::string::npos) << file.err;
  EXPECT_FALSE(fs::exists(dir.file("s")));
  EXPECT_FALSE(fs::exists(dir.file("o")));

  // The largest float itself is an isovalue like any other (no sample reaches it: no component).
  auto largest = run_child(dir.path().string(), {"-q", "validate", path, "--set", "steps.extract.iso=3.4028235e38"});
  EXPECT_EQ(largest.exit_code, 0) << largest.err;
}

TEST(MessagesCli, ADivisorOfFloatSamplesBeyondOrBelowTheFloatRangeIsRefused) {
  ScratchDir dir;
  const std::string path = dir.file("r.yaml");
  std::ofstream(path) << "version: 1\ninput:\n  synthetic: {kind: analytic, shape: [40, 40, 40]}\nsteps:\n"
                         "  - step: normalise\n    method: fixed\n    scale: 2\n  - step: extract\n    iso: 0.5\n"
                         "output:\n  directory: "
                      << dir.file("o") << "\n";
  ASSERT_EQ(run_child(dir.path().string(), {"-q", "validate", path}).exit_code, 0);
  for (const auto& [value, says] : {std::pair{"1e39", "beyond the range of a 32-bit float"},
                                    std::pair{"1e-50", "closer to 0 than a 32-bit float can hold"}}) {
    auto r = run_child(dir.path().string(), {"validate", path, "--set", std::string("steps.normalise.scale=") + value});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(std::string("parameter 'scale' is ") + value + ", " + says), std::string::npos) << r.err;
  }
}

} // namespace
} // namespace geotandem
