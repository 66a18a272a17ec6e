// One writer per store whatever the workers, and exports that never tear (issue 52, items 3 and
// 4): `geotandem` as real child processes racing on one store or one export path.

#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "cli_store_support.hpp"
#include "scratch.hpp"

namespace geotandem {
namespace {

using namespace testing;
using Args = std::vector<std::string>;

// An analytic cube large enough that a run is still going when the test stops it.
void synth_cube(const std::string& out) {
  auto r = run_geotandem("-q synth --kind analytic --shape 96 88 72 --seed 5 --out " + q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
}

std::vector<std::uint64_t> keys_of(const std::string& store) {
  std::vector<std::uint64_t> keys;
  for (const auto& row : rows_of(store))
    keys.push_back(row["key"].get<std::uint64_t>());
  return keys;
}

struct Race {
  int first = -1, second = -1;
  std::string first_err, second_err;
  bool overlapped = false; // the first still ran when the second started
};

// Starts `first`; once it holds the store (its store.json exists: written under the writer lock,
// which the run keeps until it ends) it is stopped (SIGSTOP, so that the race is not a matter of
// timing), `second` runs to its end, and the first goes on.
Race race(const ScratchDir& dir, const Args& first, const Args& second, const std::string& store) {
  Race r;
  Child a(dir.path().string(), first);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(2);
  while (!std::filesystem::exists(store + "/store.json") && std::chrono::steady_clock::now() < deadline) {
    if (a.wait_for(0)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  a.signal(SIGSTOP);
  r.overlapped = std::filesystem::exists(store + "/store.json") && !a.wait_for(0);
  auto b = run_child(dir.path().string(), second, 300);
  a.signal(SIGCONT);
  r.second = b.hung ? -1 : b.exit_code;
  r.second_err = b.err;
  const auto code = a.wait_for(300);
  r.first = code.value_or(-1);
  r.first_err = a.err();
  return r;
}

void expect_one_writer(const Race& r, const std::string& store, const std::vector<std::uint64_t>& want) {
  ASSERT_TRUE(r.overlapped) << "the first run ended before the second started: " << r.first_err;
  EXPECT_EQ(r.first, 0) << "the run that holds the store ends normally: " << r.first_err;
  EXPECT_EQ(r.second, 3) << "the second writer is refused: " << r.second_err;
  EXPECT_NE(r.second_err.find("another process is writing this store"), std::string::npos) << r.second_err;
  auto check = run_geotandem("-q store check " + q(store));
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
  EXPECT_NE(check.out.find("all intact"), std::string::npos) << check.out;
  EXPECT_EQ(keys_of(store), want) << "the store holds what one run alone extracts";
}

TEST(StoreConcurrencyCli, TwoWritersOfOneStoreAreRefusedWhateverTheWorkers) {
  // Two extractions with workers (or one with, one without) both ran and both wrote the index:
  // the directory's lock was shared, and only two in-process runs met at the shard "local".
  ScratchDir dir;
  const auto cube = dir.file("cube.raw");
  synth_cube(cube);
  const Args base = {"-q", "extract", cube, "--iso", "0.5", "--block-size", "32"};
  auto with = [&](const std::string& workers, const std::string& out) {
    Args a = base;
    a.insert(a.end(), {"--workers", workers, "--out", out});
    return a;
  };
  // The oracle: the same extraction alone.
  auto alone = run_child(dir.path().string(), with("2", dir.file("alone")), 300);
  ASSERT_EQ(alone.exit_code, 0) << alone.err;
  const auto want = keys_of(dir.file("alone"));
  ASSERT_GT(want.size(), 3u);

  const std::vector<std::pair<std::string, std::string>> pairs = {{"2", "2"}, {"0", "2"}, {"2", "0"}};
  for (const auto& [first, second] : pairs) {
    SCOPED_TRACE("workers " + first + " then " + second);
    const auto store = dir.file("s" + first + second);
    expect_one_writer(race(dir, with(first, store), with(second, store), store), store, want);
  }
}

TEST(StoreConcurrencyCli, TwoRunWorkflowsIntoOneOutputAreRefused) {
  ScratchDir dir;
  const auto cube = dir.file("cube.raw");
  synth_cube(cube);
  const auto recipe = dir.file("w.yaml");
  std::ofstream(recipe) << "version: 1\ninput:\n  file: " << cube
                        << "\nsteps:\n  - step: extract\n    iso: 0.5\n    block_size: 32\n"
                        << "output:\n  directory: " << dir.file("out") << "\n  exports: [{format: ply}]\n"
                        << "execution: {workers: 2}\n";
  auto alone =
      run_geotandem("-q extract " + q(cube) + " --iso 0.5 --block-size 32 --workers 2 --out " + q(dir.file("alone")));
  ASSERT_EQ(alone.exit_code, 0) << alone.err;
  const Args run = {"-q", "run-workflow", recipe};
  const auto store = dir.file("out/store");
  const Race r = race(dir, run, run, store);
  expect_one_writer(r, store, keys_of(dir.file("alone")));
  EXPECT_NE(file_text(dir.file("out/report.html")).find("</html>"), std::string::npos);
}

TEST(StoreConcurrencyCli, ConcurrentExportsToOnePathNeverTear) {
  // Both wrote NAME.part: the file kept the header of one export and the body of the other.
  ScratchDir dir;
  const auto cube = dir.file("cube.raw"), store = dir.file("store");
  synth_cube(cube);
  ASSERT_EQ(run_geotandem("-q extract " + q(cube) + " --iso 0.5 --workers 0 --out " + q(store)).exit_code, 0);
  const auto rows = rows_of(store);
  ASSERT_GT(rows.size(), 4u);
  // Two different exports (every body, and the larger half), so that a mix of them shows.
  std::vector<double> volumes;
  for (const auto& row : rows)
    volumes.push_back(row["volume"].get<double>());
  std::sort(volumes.begin(), volumes.end());
  const std::string median = std::to_string(volumes[volumes.size() / 2]);
  const Args all = {"-q", "store", "export", store, "--format", "obj", "--overwrite", "--out"};
  Args half = all;
  half.insert(half.end() - 1, {"--min-volume", median});
  auto export_to = [&](Args args, const std::string& path) {
    args.push_back(path);
    return args;
  };
  ASSERT_EQ(run_child(dir.path().string(), export_to(all, dir.file("all.obj"))).exit_code, 0);
  ASSERT_EQ(run_child(dir.path().string(), export_to(half, dir.file("half.obj"))).exit_code, 0);
  const std::string whole_all = file_text(dir.file("all.obj")), whole_half = file_text(dir.file("half.obj"));
  ASSERT_NE(whole_all, whole_half);

  const auto target = dir.file("exports/bodies.obj");
  std::filesystem::create_directories(dir.file("exports"));
  for (int round = 0; round < 8; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    Child a(dir.path().string(), export_to(all, target));
    Child b(dir.path().string(), export_to(half, target));
    ASSERT_EQ(a.wait_for(120), std::optional<int>(0)) << a.err();
    ASSERT_EQ(b.wait_for(120), std::optional<int>(0)) << b.err();
    const std::string got = file_text(target);
    EXPECT_TRUE(got == whole_all || got == whole_half)
        << "the file is neither export whole (" << got.size() << " bytes; the exports have " << whole_all.size()
        << " and " << whole_half.size() << ")";
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.file("exports")))
      ++entries;
    EXPECT_EQ(entries, 1u) << "no temporary file is left beside the export";
  }
}

} // namespace
} // namespace geotandem
