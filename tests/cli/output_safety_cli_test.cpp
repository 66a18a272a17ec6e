// Outputs that never clobber: exports and cubes that replace only earlier outputs, never the input,
// a file inside a store, a device, a FIFO or a directory; a report that never replaces a file
// outside the output directory. `geotandem` as a real child process.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "child_process.hpp"
#include "cli_store_support.hpp"
#include "scratch.hpp"

namespace geotandem {
namespace {

using namespace testing; // geotandem::testing: the child process, scratch directories, store helpers

TEST(OutputSafetyCli, ExportsNeverClobberAFileNorWriteInsideAStore) {
  ScratchDir dir;
  const auto cube = dir.file("cube.raw"), store = dir.file("store");
  synth(cube, 3);
  ASSERT_EQ(run_geotandem("-q extract " + q(cube) + " --iso 0.5 --out " + q(store)).exit_code, 0);
  const auto cube_bytes = file_text(cube), index_bytes = file_text(dir.file("store/index.sqlite"));

  auto into_index = run_geotandem("-q store export " + q(store) + " --format obj --out " +
                                  q(dir.file("store/index.sqlite")) + " --overwrite");
  EXPECT_EQ(into_index.exit_code, 2) << into_index.err;
  EXPECT_NE(into_index.err.find("inside a store"), std::string::npos) << into_index.err;
  auto per_component = run_geotandem("-q store export " + q(store) + " --format obj --per-component --out " +
                                     q(dir.file("store/shards")));
  EXPECT_EQ(per_component.exit_code, 2) << per_component.err;
  EXPECT_EQ(file_text(dir.file("store/index.sqlite")), index_bytes);
  EXPECT_EQ(run_geotandem("-q store check " + q(store)).exit_code, 0);

  auto onto_cube = run_geotandem("-q store export " + q(store) + " --format obj --out " + q(cube));
  EXPECT_EQ(onto_cube.exit_code, 3) << onto_cube.err;
  EXPECT_NE(onto_cube.err.find("--overwrite"), std::string::npos) << onto_cube.err;
  EXPECT_EQ(file_text(cube), cube_bytes) << "the input cube was overwritten";

  ASSERT_EQ(run_geotandem("-q store export " + q(store) + " --format obj --out " + q(dir.file("b.obj"))).exit_code, 0);
  EXPECT_EQ(run_geotandem("-q store export " + q(store) + " --format obj --out " + q(dir.file("b.obj"))).exit_code, 3);
  EXPECT_EQ(
      run_geotandem("-q store export " + q(store) + " --format obj --out " + q(dir.file("b.obj")) + " --overwrite")
          .exit_code,
      0);
  ASSERT_EQ(run_geotandem("-q store export " + q(store) + " --format ply --per-component --out " + q(dir.file("each")))
                .exit_code,
            0);
  EXPECT_EQ(run_geotandem("-q store export " + q(store) + " --format ply --per-component --out " + q(dir.file("each")))
                .exit_code,
            3);
}

TEST(OutputSafetyCli, CubesAreNeverWrittenOverTheInputNorInsideAStore) {
  ScratchDir dir;
  const auto cube = dir.file("cube.raw"), store = dir.file("store");
  synth(cube, 3);
  const auto cube_bytes = file_text(cube);
  {
    // The attribute cube named after the input, one directory up from the output directory.
    std::ofstream recipe(dir.file("w.yaml"));
    recipe << "version: 1\ninput:\n  file: cube.raw\nsteps:\n  - step: extract\n    input: input\n    iso: 0.5\n"
           << "output:\n  directory: " << dir.file("w-out") << "\n  attribute: ../cube.raw\n";
  }
  auto r = run_geotandem("-q run-workflow " + q(dir.file("w.yaml")));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("already exists"), std::string::npos) << r.err;
  EXPECT_EQ(file_text(cube), cube_bytes) << "the input cube was overwritten";
  auto fresh = run_geotandem("-q run-workflow " + q(dir.file("w.yaml")) + " --fresh");
  EXPECT_EQ(fresh.exit_code, 3) << fresh.err;
  EXPECT_EQ(file_text(cube), cube_bytes) << "--fresh overwrote the input cube";

  ASSERT_EQ(run_geotandem("-q extract " + q(cube) + " --iso 0.5 --out " + q(store)).exit_code, 0);
  auto inside = run_geotandem("-q synth --kind analytic --shape 40 40 40 --out " + q(store + "/shards/x.raw"));
  EXPECT_EQ(inside.exit_code, 2) << inside.err;
  EXPECT_NE(inside.err.find("inside a component store"), std::string::npos) << inside.err;
  EXPECT_FALSE(std::filesystem::exists(store + "/shards/x.raw"));
}

TEST(OutputSafetyCli, OverwriteReplacesEarlierOutputsOnlyNeverADeviceAFifoOrADirectory) {
  // As root, `--out /dev/null --overwrite` removed the device and put a file in its place; a
  // directory named like a raw cube was removed with everything in it.
  namespace fs = std::filesystem;
  ScratchDir dir;
  const auto cube = dir.file("cube.raw"), store = dir.file("store");
  synth(cube, 3);
  ASSERT_EQ(run_geotandem("-q extract " + q(cube) + " --iso 0.5 --out " + q(store)).exit_code, 0);
  const std::string synth_args = "-q synth --kind analytic --shape 40 40 40 --overwrite --out ";

  ASSERT_EQ(::mkfifo(dir.file("pipe.raw").c_str(), 0644), 0);
  ASSERT_EQ(::mkfifo(dir.file("pipe.ply").c_str(), 0644), 0);
  fs::create_directories(dir.file("folder.segy"));
  std::ofstream(dir.file("folder.segy/keep.txt")) << "the user's file";
  std::vector<std::pair<std::string, std::string>> refused = {
      {synth_args + q(dir.file("pipe.raw")), "a FIFO"},
      {synth_args + q(dir.file("folder.segy")), "a directory"},
      {"-q store export " + q(store) + " --format ply --overwrite --out " + q(dir.file("pipe.ply")), "a FIFO"}};
  // A device node needs root (the machines run as root; elsewhere that case is left out).
  const bool device = ::mknod(dir.file("null.tif").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0;
  if (device) refused.push_back({synth_args + q(dir.file("null.tif")), "a character device"});
  for (const auto& [command, kind] : refused) {
    auto r = run_geotandem(command);
    EXPECT_EQ(r.exit_code, 3) << command << ": " << r.err;
    EXPECT_NE(r.err.find("will not replace the output path: it is " + kind), std::string::npos) << r.err;
  }
  EXPECT_TRUE(fs::is_fifo(dir.file("pipe.raw")));
  EXPECT_TRUE(fs::is_fifo(dir.file("pipe.ply")));
  EXPECT_EQ(file_text(dir.file("folder.segy/keep.txt")), "the user's file");
  if (device) {
    EXPECT_TRUE(fs::is_character_file(dir.file("null.tif")));
  }

  // An earlier output, and a link to one (the link is replaced, not what it points to), are.
  std::ofstream(dir.file("old.ply")) << "an earlier export";
  fs::create_symlink(dir.file("old.ply"), dir.file("link.ply"));
  EXPECT_EQ(run_geotandem("-q store export " + q(store) + " --format ply --overwrite --out " + q(dir.file("link.ply")))
                .exit_code,
            0);
  EXPECT_FALSE(fs::is_symlink(dir.file("link.ply")));
  EXPECT_EQ(file_text(dir.file("old.ply")), "an earlier export");
  EXPECT_EQ(run_geotandem(synth_args + q(cube)).exit_code, 0);
}

TEST(OutputSafetyCli, AReportNeverReplacesAFileOutsideTheOutputDirectoryNorWritesIntoAFifo) {
  // The report was written with a plain truncating open: `report: ../notes.html` replaced the
  // user's file, and a FIFO at the report's path blocked the run forever.
  ScratchDir dir;
  const auto cube = dir.file("cube.raw");
  synth(cube, 3);
  const auto recipe = [&](const std::string& report) {
    std::ofstream(dir.file("w.yaml")) << "version: 1\ninput:\n  file: cube.raw\nsteps:\n  - step: extract\n"
                                      << "    input: input\n    iso: 0.5\noutput:\n  directory: " << dir.file("out")
                                      << "\n  report: " << report << "\n  exports: []\n";
  };
  std::ofstream(dir.file("notes.html")) << "the user's notes";
  recipe("../notes.html");
  auto outside = run_geotandem("-q run-workflow " + q(dir.file("w.yaml")));
  EXPECT_EQ(outside.exit_code, 3) << outside.err;
  EXPECT_NE(outside.err.find("outside the output directory"), std::string::npos) << outside.err;
  // The error says which step of the recipe, and where: the report's is the output section (line 9).
  EXPECT_NE(outside.err.find("in the recipe's step 'report' at " + dir.file("w.yaml") + ":9:"), std::string::npos)
      << outside.err;
  EXPECT_EQ(file_text(dir.file("notes.html")), "the user's notes");
  EXPECT_FALSE(rows_of(dir.file("out/store")).empty()) << "the extraction before the report was lost";

  recipe("report.html"); // inside: each run replaces its own report
  ASSERT_EQ(run_geotandem("-q run-workflow " + q(dir.file("w.yaml"))).exit_code, 0);
  ASSERT_EQ(run_geotandem("-q run-workflow " + q(dir.file("w.yaml"))).exit_code, 0);
  EXPECT_NE(file_text(dir.file("out/report.html")).find("<html"), std::string::npos);

  std::filesystem::remove(dir.file("out/report.html"));
  ASSERT_EQ(::mkfifo(dir.file("out/report.html").c_str(), 0644), 0);
  auto fifo = testing::run_child(dir.path().string(), {"-q", "run-workflow", dir.file("w.yaml")}, 60);
  ASSERT_FALSE(fifo.hung) << "the run blocked on the FIFO";
  EXPECT_EQ(fifo.exit_code, 3) << fifo.err;
  EXPECT_TRUE(std::filesystem::is_fifo(dir.file("out/report.html")));
}

TEST(OutputSafetyCli, ValidateRefusesOutputsThatAreTheRunsOwnFiles) {
  // An export named report.html or state.json passed validate and was replaced by the report or
  // the state; `store: .` made the output directory the store; two exports named once relatively
  // and once absolutely wrote one file.
  ScratchDir dir;
  const auto out = dir.file("out"), recipe = dir.file("w.yaml");
  const auto write = [&](const std::string& output) {
    std::ofstream(recipe) << "version: 1\ninput:\n  synthetic: {kind: analytic, shape: [40, 40, 40]}\nsteps:\n"
                          << "  - step: extract\n    iso: 0.5\noutput:\n  directory: " << out << "\n"
                          << output;
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"  exports:\n    - {format: ply, path: report.html}\n",
       ":10:7: export 1 writes report.html, which is the run's report (report.html)"},
      {"  exports:\n    - {format: obj, path: state.json}\n",
       ":10:7: export 1 writes state.json, which is the run's state file (state.json)"},
      {"  exports:\n    - {format: ply, path: truth.json}\n",
       ":10:7: export 1 writes truth.json, which is the synthetic"},
      {"  exports:\n    - {format: ply, path: store/x.ply}\n",
       ":10:7: export 1 writes store/x.ply, which is the run's store"},
      {"  exports:\n    - {format: ply, path: .}\n", ":10:7: export 1 writes ., the output directory itself"},
      {"  store: .\n", ":9:10: output.store '.': the store would be the output directory itself"},
      {"  store: ..\n", ":9:10: output.store '..': the store would hold the output directory"},
      {"  report: state.json\n", ":9:11: the report writes state.json, which is the run's state file"},
      {"  exports:\n    - {format: ply, path: bodies.ply}\n    - {format: ply, path: " + out + "/./bodies.ply}\n",
       ":11:7: export 2 writes " + out + "/./bodies.ply, like an earlier export (export 1 writes bodies.ply"},
  };
  for (const auto& [output, message] : cases) {
    write(output);
    for (const std::string command : {"validate", "run-workflow"}) {
      auto r = run_geotandem("-q " + command + " " + q(recipe));
      EXPECT_EQ(r.exit_code, 2) << command << "\n" << output << r.err;
      EXPECT_NE(r.err.find(recipe + message), std::string::npos) << output << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(out)) << "nothing is written: " << output;
  }
  write("  exports:\n    - {format: ply, path: bodies.ply}\n    - {format: ply, per_component: true, path: .}\n");
  auto fine = run_geotandem("-q validate " + q(recipe));
  EXPECT_EQ(fine.exit_code, 0) << "one file per component may go into the output directory: " << fine.err;
}

} // namespace
} // namespace geotandem
