// Stores that refuse mixed runs, damaged records found and repaired, two writers on one store:
// `geotandem` as a real child process on real cubes written by `geotandem synth`. What the
// outputs never clobber is in output_safety_cli_test.cpp.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "cli_store_support.hpp"
#include "geotandem/store/store.hpp"
#include "scratch.hpp"
#include "test_paths.hpp"

namespace geotandem {
namespace {

using namespace testing; // geotandem::testing: the child process, scratch directories, store helpers

TEST(StoreSafetyCli, ResumingWithOtherParametersIsRefusedAndListsTheDifferences) {
  ScratchDir dir;
  const auto cube = dir.file("cube.raw"), store = dir.file("store");
  synth(cube, 3);
  auto first = run_geotandem("-q extract " + q(cube) + " --iso 0.5 --out " + q(store));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const auto before = rows_of(store);
  ASSERT_GT(before.size(), 3u);

  // Another isovalue, another max-error, another axis, another mode: each refused, nothing added.
  for (const std::string& change :
       {std::string("--iso 0.6"), std::string("--iso 0.5 --max-error 0.9"), std::string("--iso 0.5 --axis j"),
        std::string("--iso 0.5 --mode brute"), std::string("--iso 0.5 --block-size 16")}) {
    auto r = run_geotandem("-q extract " + q(cube) + " " + change + " --out " + q(store));
    EXPECT_EQ(r.exit_code, 2) << change << "\n" << r.err;
    EXPECT_NE(r.err.find("another extraction"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--out"), std::string::npos) << "says how to proceed: " << r.err;
    EXPECT_EQ(rows_of(store).size(), before.size()) << change << " mixed components into the store";
  }
  auto r = run_geotandem("-q extract " + q(cube) + " --iso 0.6 --max-error 0.9 --out " + q(store));
  EXPECT_NE(r.err.find("iso: 0.5 in the store, 0.6 now"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("max_error: 0.5 in the store, 0.9 now"), std::string::npos) << r.err;

  EXPECT_NE(r.err.find("--fresh"), std::string::npos) << r.err;

  // The same extraction resumes: everything is already there.
  auto again = run_geotandem("-q extract " + q(cube) + " --iso 0.5 --out " + q(store));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("(" + std::to_string(before.size()) + " already in the store)"), std::string::npos)
      << again.out;
  EXPECT_EQ(rows_of(store), before);

  // --fresh replaces the store: it then holds what a clean iso-0.6 extraction holds.
  auto fresh = run_geotandem("-q extract " + q(cube) + " --iso 0.6 --fresh --out " + q(store));
  ASSERT_EQ(fresh.exit_code, 0) << fresh.err;
  ASSERT_EQ(run_geotandem("-q extract " + q(cube) + " --iso 0.6 --out " + q(dir.file("clean"))).exit_code, 0);
  EXPECT_EQ(rows_of(store), rows_of(dir.file("clean")));
}

TEST(StoreSafetyCli, ResumingOnAReplacedCubeOfTheSameShapeIsRefused) {
  ScratchDir dir;
  const auto cube = dir.file("cube.raw"), store = dir.file("store");
  synth(cube, 3);
  ASSERT_EQ(run_geotandem("-q extract " + q(cube) + " --iso 0.5 --out " + q(store)).exit_code, 0);
  const auto before = rows_of(store);
  synth(dir.file("other.raw"), 4);
  std::filesystem::copy_file(dir.file("other.raw"), cube, std::filesystem::copy_options::overwrite_existing);
  std::filesystem::copy_file(dir.file("other.raw.json"), cube + ".json",
                             std::filesystem::copy_options::overwrite_existing);
  auto r = run_geotandem("-q extract " + q(cube) + " --iso 0.5 --out " + q(store));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("input."), std::string::npos) << "names the input as what differs: " << r.err;
  EXPECT_EQ(rows_of(store), before);
}

TEST(StoreSafetyCli, WorkflowDoesNotReuseAnExtractionOfAReplacedCube) {
  ScratchDir dir;
  const auto cube = dir.file("cube.raw");
  synth(cube, 3);
  synth(dir.file("other.raw"), 4);
  {
    std::ofstream recipe(dir.file("w.yaml"));
    recipe << "version: 1\ninput:\n  file: cube.raw\nsteps:\n  - step: extract\n    input: input\n    iso: 0.5\n"
           << "output:\n  directory: " << dir.file("w-out") << "\n";
  }
  auto first = run_geotandem("-q run-workflow " + q(dir.file("w.yaml")));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  std::filesystem::copy_file(dir.file("other.raw"), cube, std::filesystem::copy_options::overwrite_existing);
  std::filesystem::copy_file(dir.file("other.raw.json"), cube + ".json",
                             std::filesystem::copy_options::overwrite_existing);
  auto second = run_geotandem("run-workflow " + q(dir.file("w.yaml")));
  EXPECT_EQ(second.exit_code, 2) << second.err;
  EXPECT_EQ(second.err.find("reusing the finished extraction"), std::string::npos) << second.err;
  EXPECT_NE(second.err.find("--fresh"), std::string::npos) << second.err;

  // With --fresh the store holds what a clean extraction of the new cube holds.
  auto fresh = run_geotandem("-q run-workflow " + q(dir.file("w.yaml")) + " --fresh");
  ASSERT_EQ(fresh.exit_code, 0) << fresh.err;
  ASSERT_EQ(run_geotandem("-q extract " + q(dir.file("other.raw")) + " --iso 0.5 --block-size 128 --out " +
                          q(dir.file("clean")))
                .exit_code,
            0);
  std::set<std::uint64_t> got, want;
  for (const auto& row : rows_of(dir.file("w-out/store")))
    got.insert(row["key"].get<std::uint64_t>());
  for (const auto& row : rows_of(dir.file("clean")))
    want.insert(row["key"].get<std::uint64_t>());
  EXPECT_FALSE(want.empty());
  EXPECT_EQ(got, want);
}

TEST(StoreSafetyCli, FreshRefusesWhileAnotherProcessWritesTheStore) {
  ScratchDir dir;
  synth(dir.file("cube.raw"), 3);
  {
    std::ofstream recipe(dir.file("w.yaml"));
    recipe << "version: 1\ninput:\n  file: cube.raw\nsteps:\n  - step: extract\n    input: input\n    iso: 0.5\n"
           << "output:\n  directory: " << dir.file("w-out") << "\n";
  }
  ASSERT_EQ(run_geotandem("-q run-workflow " + q(dir.file("w.yaml"))).exit_code, 0);
  const auto before = rows_of(dir.file("w-out/store"));
  {
    // This test process is the other writer: it holds the store open for writing.
    auto writer = store::ComponentStore::open(dir.file("w-out/store"), store::OpenMode::read_write);
    auto r = run_geotandem("-q run-workflow " + q(dir.file("w.yaml")) + " --set steps.extract.iso=0.6 --fresh");
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_NE(r.err.find("another process is writing this store"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("removed the previous store"), std::string::npos) << "nothing was removed: " << r.err;
    EXPECT_TRUE(store::ComponentStore::exists(dir.file("w-out/store")));
    EXPECT_EQ(writer.size(), before.size());
  }
  auto r = run_geotandem("run-workflow " + q(dir.file("w.yaml")) + " --set steps.extract.iso=0.6 --fresh");
  EXPECT_EQ(r.exit_code, 0) << "once the writer is gone --fresh proceeds: " << r.err;
  EXPECT_NE(r.err.find("removed the previous store"), std::string::npos) << r.err;
}

TEST(StoreSafetyCli, CheckFindsADamagedRecordExportSkipsItAndARerunRepairsIt) {
  ScratchDir dir;
  const auto cube = dir.file("cube.raw"), store = dir.file("store");
  synth(cube, 3);
  ASSERT_EQ(run_geotandem("-q extract " + q(cube) + " --iso 0.5 --out " + q(store)).exit_code, 0);
  auto rows = rows_of(store);
  ASSERT_GT(rows.size(), 3u);
  auto clean = run_geotandem("-q store check " + q(store));
  EXPECT_EQ(clean.exit_code, 0) << clean.err;
  EXPECT_NE(clean.out.find("checked " + std::to_string(rows.size()) + " components"), std::string::npos) << clean.out;

  // Flip one byte in the middle of the second record.
  const auto& victim = rows[1];
  const auto shard = dir.file("store/shards/" + victim["shard"].get<std::string>() + ".gts");
  {
    std::fstream f(shard, std::ios::in | std::ios::out | std::ios::binary);
    const auto at =
        static_cast<std::streamoff>(victim["offset"].get<std::uint64_t>() + victim["length"].get<std::uint64_t>() / 2);
    f.seekg(at);
    char c = 0;
    f.read(&c, 1);
    c = static_cast<char>(c ^ 0x5a);
    f.seekp(at);
    f.write(&c, 1);
  }
  const auto key = std::to_string(victim["key"].get<std::uint64_t>());
  auto check = run_geotandem("-q store check --json " + q(store));
  EXPECT_EQ(check.exit_code, 4) << check.err;
  auto report = nlohmann::json::parse(check.out);
  ASSERT_EQ(report["damaged"].size(), 1u) << check.out;
  EXPECT_EQ(report["damaged"][0]["key"], victim["key"]);
  EXPECT_EQ(report["checked"], rows.size());

  auto stops = run_geotandem("-q store export " + q(store) + " --format ply --out " + q(dir.file("all.ply")));
  EXPECT_EQ(stops.exit_code, 4) << stops.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("all.ply")));
  auto skips = run_geotandem("-q store export " + q(store) + " --format ply --out " + q(dir.file("all.ply")) +
                             " --skip-damaged");
  ASSERT_EQ(skips.exit_code, 0) << skips.err;
  EXPECT_NE(skips.out.find("skipped 1 damaged component: " + key), std::string::npos) << skips.out;
  EXPECT_NE(skips.out.find("exported " + std::to_string(rows.size() - 1) + " components"), std::string::npos)
      << skips.out;

  // A rerun of the same extraction writes the damaged one again.
  auto rerun = run_geotandem("-q extract " + q(cube) + " --iso 0.5 --out " + q(store));
  ASSERT_EQ(rerun.exit_code, 0) << rerun.err;
  EXPECT_EQ(run_geotandem("-q store check " + q(store)).exit_code, 0);
  auto after = rows_of(store);
  ASSERT_EQ(after.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(after[i]["key"], rows[i]["key"]);
    EXPECT_EQ(after[i]["checksum"], rows[i]["checksum"]) << "the same surface, written again";
    EXPECT_EQ(after[i]["volume"], rows[i]["volume"]);
  }
  EXPECT_EQ(run_geotandem("-q store export " + q(store) + " --format ply --out " + q(dir.file("again.ply"))).exit_code,
            0);
}

TEST(StoreSafetyCli, TwoExtractionsStartingOnOneNewStoreNeverBreakIt) {
  // Both used to build the index at once ("index statement failed: disk I/O error"), or one took
  // the other's half-made store for an interrupted creation and deleted it.
  ScratchDir dir;
  const auto cube = dir.file("cube.raw");
  synth(cube, 3);
  const std::vector<std::string> extract = {"-q", "extract", cube, "--iso", "0.5", "--workers", "0", "--out"};

  // Deterministic: this process is a creator half-way (a bare index, the directory locked).
  const auto half = dir.file("half");
  std::filesystem::create_directories(half + "/shards");
  std::ofstream(half + "/index.sqlite") << "";
  {
    const int fd = ::open(half.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
    auto args = extract;
    args.push_back(half);
    auto r = testing::run_child(dir.path().string(), args, 60);
    ::close(fd);
    ASSERT_FALSE(r.hung);
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_NE(r.err.find("another process is writing this store"), std::string::npos) << r.err;
    EXPECT_TRUE(std::filesystem::exists(half + "/index.sqlite")) << "the creator's files were deleted";
  }
  auto args = extract;
  args.push_back(half);
  auto alone = testing::run_child(dir.path().string(), args, 60); // the creator is gone: a fresh start
  EXPECT_EQ(alone.exit_code, 0) << alone.err;
  const auto want = rows_of(half);

  // Two real processes started together, a few times: whichever loses says why, and the store is whole.
  for (int round = 0; round < 3; ++round) {
    const auto store = dir.file("race" + std::to_string(round));
    auto with_store = extract;
    with_store.push_back(store);
    testing::Child first(dir.path().string(), with_store), second(dir.path().string(), with_store);
    const auto a = first.wait_for(60), b = second.wait_for(60);
    ASSERT_TRUE(a && b) << "an extraction hung";
    EXPECT_TRUE(*a == 0 || *b == 0) << first.err() << second.err();
    for (const auto* child : {&first, &second}) {
      if (child == &first ? *a == 0 : *b == 0) continue;
      EXPECT_EQ(child == &first ? *a : *b, 3) << child->err();
      EXPECT_NE(child->err().find("another process"), std::string::npos) << child->err();
    }
    EXPECT_EQ(run_geotandem("-q store check " + q(store)).exit_code, 0);
    EXPECT_EQ(rows_of(store).size(), want.size());
  }
}

TEST(StoreSafetyCli, ARunWithoutComponentsWarns) {
  ScratchDir dir;
  const auto cube = dir.file("cube.raw"), store = dir.file("store");
  synth(cube, 3);
  auto r = run_geotandem("extract " + q(cube) + " --iso 1e9 --out " + q(store));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: no component was extracted"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'geotandem info' on the cube shows it"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("--stats"), std::string::npos) << "info has no --stats option: " << r.err;
  auto runs = run_geotandem("store runs --json " + q(store));
  ASSERT_EQ(runs.exit_code, 0);
  auto list = nlohmann::json::parse(runs.out);
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0]["statistics"]["warnings"].size(), 1u) << runs.out;

  // run-workflow: the report says so too.
  {
    std::ofstream recipe(dir.file("w.yaml"));
    recipe << "version: 1\ninput:\n  file: cube.raw\nsteps:\n  - step: extract\n    input: input\n    iso: 1e9\n"
           << "output:\n  directory: " << dir.file("w-out") << "\n";
  }
  auto w = run_geotandem("-q run-workflow " + q(dir.file("w.yaml")));
  ASSERT_EQ(w.exit_code, 0) << w.err;
  EXPECT_NE(w.err.find("no component was extracted"), std::string::npos) << w.err;
  EXPECT_NE(file_text(dir.file("w-out/report.html")).find("WARNING: no component was extracted"), std::string::npos);

  // Extracting an attribute, the hint is about the attribute's range, not the cube's.
  {
    std::ofstream recipe(dir.file("a.yaml"));
    recipe << "version: 1\ninput:\n  file: cube.raw\nsteps:\n  - step: envelope\n    input: input\n"
           << "  - step: extract\n    input: envelope\n    iso: 1e9\noutput:\n  directory: " << dir.file("a-out")
           << "\n";
  }
  auto a = run_geotandem("-q run-workflow " + q(dir.file("a.yaml")));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_NE(a.err.find("inside the attribute's value range? (write the attribute with output.attribute"),
            std::string::npos)
      << a.err;
}

TEST(StoreSafetyCli, AStoreThisUserCannotWriteIsListedCheckedAndExported) {
  ScratchDir dir;
  const auto cube = dir.file("cube.raw"), store = dir.file("store");
  ASSERT_EQ(run_geotandem("-q synth --kind analytic --shape 160 160 120 --out " + q(cube)).exit_code, 0);
  {
    // A writer killed mid-run leaves the index's WAL files behind, as on a copied or archived store. It
    // is killed once the index holds a component, not after a fixed time: on a slow machine the first
    // component can take longer than any guess (an empty store has nothing to export).
    testing::Child writer(dir.path().string(), {"-q", "extract", cube, "--iso", "0.5", "--out", store});
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(2);
    bool committed = false;
    while (!committed && std::chrono::steady_clock::now() < deadline) {
      if (writer.wait_for(0.05)) break; // finished first: its WAL files stay behind all the same
      if (!std::filesystem::exists(store + "/store.json")) continue;
      auto r = run_geotandem("-q store ls --json " + q(store));
      const auto rows = nlohmann::json::parse(r.out, nullptr, false);
      committed = r.exit_code == 0 && rows.is_array() && !rows.empty();
    }
    ASSERT_TRUE(committed || writer.wait_for(0)) << "no component committed within 2 min: " << writer.err();
    writer.signal(SIGKILL);
    ASSERT_TRUE(writer.wait_for(30)) << "the writer did not end after SIGKILL";
  }
  // Another user (root runs the commands as nobody through a user namespace) may read, not write.
  std::string as_other;
  if (::geteuid() == 0) {
    if (std::system("unshare --user true >/dev/null 2>&1") != 0) GTEST_SKIP() << "no user namespaces here";
    as_other = "unshare --user ";
  }
  namespace fs = std::filesystem;
  for (const auto& entry : fs::recursive_directory_iterator(store))
    fs::permissions(entry.path(), fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write,
                    fs::perm_options::remove);
  fs::permissions(store, fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write,
                  fs::perm_options::remove);
  fs::create_directories(dir.file("exports"));
  fs::permissions(dir.file("exports"), fs::perms::all, fs::perm_options::add);
  auto run = [&](const std::string& args) {
    const std::string base = dir.file("ro");
    int status = std::system(
        (as_other + "'" + test_paths::binary() + "' " + args + " >" + base + ".out 2>" + base + ".err </dev/null")
            .c_str());
    return std::make_pair(WIFEXITED(status) ? WEXITSTATUS(status) : -1, file_text(base + ".err"));
  };
  auto ls = run("-q store ls --json " + q(store));
  ASSERT_EQ(ls.first, 0) << ls.second;
  EXPECT_FALSE(nlohmann::json::parse(file_text(dir.file("ro.out"))).empty()) << "the WAL's components are listed";
  auto check = run("-q store check " + q(store));
  EXPECT_EQ(check.first, 0) << check.second;
  auto exported = run("-q store export " + q(store) + " --format ply --out " + q(dir.file("exports/all.ply")));
  EXPECT_EQ(exported.first, 0) << exported.second;
  auto resumed = run("-q extract " + q(cube) + " --iso 0.5 --out " + q(store));
  EXPECT_EQ(resumed.first, 3) << "writing is refused as an I/O error: " << resumed.second;
  for (const auto& entry : fs::recursive_directory_iterator(store))
    fs::permissions(entry.path(), fs::perms::owner_write, fs::perm_options::add);
  fs::permissions(store, fs::perms::owner_write, fs::perm_options::add);
}

} // namespace
} // namespace geotandem
