// The manager/worker runtime with real processes and real sockets: `geotandem extract --workers N`
// against the in-process extraction, workers killed or frozen at random moments, a manager killed
// and rerun, Ctrl-C on the manager.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <random>
#include <thread>

#include <nlohmann/json.hpp>

#include "geotandem/store/store.hpp"
#include "process_fixtures.hpp"
#include "scratch.hpp"
#include "test_paths.hpp"

namespace geotandem::testing {
namespace {

// An analytic cube whose planted bodies cross block planes, split into leaves of 8 cells: every
// body crosses many block faces.
struct Fixture {
  ScratchDir dir;
  std::string cube = dir.file("cube.raw");
  std::map<std::uint64_t, StoredComponent> reference;

  Fixture() {
    auto r = run_geotandem("-q synth --kind analytic --shape 48 44 40 --seed 3 --out '" + cube + "'");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    r = run_geotandem("-q extract '" + cube + "' --iso 0.5 --block-size 8 --workers 0 --out '" + dir.file("ref") + "'");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    reference = components_of(dir.file("ref"), true);
  }

  std::vector<std::string> extract_args(const std::string& out, int workers) const {
    return {"-q",        "--log-level",           "debug", "extract",    cube, "--iso", "0.5", "--block-size", "8",
            "--workers", std::to_string(workers), "--out", dir.file(out)};
  }

  // Same keys, volumes within 0.5 %, closed 2-manifolds where the reference is closed.
  void expect_same(const std::string& out, bool check_meshes = true) const {
    const auto got = components_of(dir.file(out), check_meshes);
    ASSERT_GT(reference.size(), 5u);
    ASSERT_EQ(got.size(), reference.size()) << out;
    for (const auto& [key, ref] : reference) {
      ASSERT_TRUE(got.count(key)) << "component " << key << " missing from " << out;
      const StoredComponent& c = got.at(key);
      EXPECT_NEAR(c.volume, ref.volume, 0.005 * std::abs(ref.volume) + 1e-9) << "component " << key;
      EXPECT_EQ(c.closed, ref.closed) << "component " << key;
      if (check_meshes && !ref.cut) {
        EXPECT_TRUE(c.manifold) << "component " << key << " is not a closed 2-manifold";
      }
    }
  }
};

TEST(Workers, OneTwoAndFourWorkersGiveTheComponentsOfTheInProcessRun) {
  Fixture f;
  for (int workers : {1, 2, 4}) {
    const std::string out = "w" + std::to_string(workers);
    const pid_t pid = spawn_geotandem(f.extract_args(out, workers), f.dir.file(out + ".log"));
    ASSERT_EQ(wait_exit(pid, 300), 0) << read_text(f.dir.file(out + ".log"));
    f.expect_same(out);
    // The run's totals come back with the final surface: as many marching-cubes triangles as the
    // in-process run, and collapses counted (not the zeros of a report that lost them).
    const auto stats = [&](const std::string& name) {
      const auto runs = store::ComponentStore::open(f.dir.file(name)).runs();
      return nlohmann::json::parse(runs.back().statistics);
    };
    const nlohmann::json got = stats(out), ref = stats("ref");
    EXPECT_EQ(got.at("input_triangles").get<std::uint64_t>(), ref.at("input_triangles").get<std::uint64_t>()) << out;
    EXPECT_GT(got.at("collapses").get<std::uint64_t>(), got.at("input_triangles").get<std::uint64_t>() / 4) << out;
    // Every counter of the collapse loop comes back with them (the DONE after FINISHED), and holds
    // what a loop's counters hold: the same triangles and collapses, every collapse evaluated first,
    // every component dumped counted, as in the in-process run.
    for (const nlohmann::json* run : {&got, &ref}) {
      const nlohmann::json& c = run->at("counters");
      EXPECT_EQ(c.at("input_triangles"), run->at("input_triangles")) << out;
      EXPECT_EQ(c.at("collapses"), run->at("collapses")) << out;
      EXPECT_GE(c.at("evaluations").get<std::uint64_t>(), c.at("collapses").get<std::uint64_t>()) << out;
      EXPECT_EQ(c.at("components_dumped"), run->at("components")) << out;
      EXPECT_GT(c.at("blocked_by_faces").get<std::uint64_t>(), 0u) << out << ": blocks of 8 park edges at their faces";
    }
    // The triangles the workers held together, as each reported after its tasks: some (the block
    // faces keep surfaces waiting for their brothers), never more than marching cubes made.
    const auto held = got.at("peak_held_triangles").get<std::uint64_t>();
    EXPECT_GT(held, 0u) << out;
    EXPECT_LE(held, got.at("input_triangles").get<std::uint64_t>()) << out;
    EXPECT_NE(read_text(f.dir.file(out + ".log")).find("triangles held by the workers: " + std::to_string(held)),
              std::string::npos)
        << "the peak is one of the totals logged";
  }
}

// The quickstart recipe (a synthetic seismic cube, a chaos and envelope attribute chain) with its
// chain rebuilt and fused block by block in 2 and 3 workers, against the in-process run.
TEST(Workers, ARecipesAttributeChainRunsInTheWorkers) {
  ScratchDir dir;
  const std::string recipe = test_paths::workflows() + "/quickstart.yaml";
  const std::string small = " --set 'input.synthetic.shape=[64,64,48]' --set steps.extract.block_size=16";
  auto r = run_geotandem("-q run-workflow '" + recipe + "' --set output.directory='" + dir.file("w1") + "'" + small);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto reference = components_of(dir.file("w1") + "/store", false);
  ASSERT_GT(reference.size(), 5u);
  for (int workers : {2, 3}) {
    const std::string out = dir.file("w" + std::to_string(workers));
    r = run_geotandem("--log-level info run-workflow '" + recipe + "' --set output.directory='" + out +
                      "' --set execution.workers=" + std::to_string(workers) + small);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("extracting with " + std::to_string(workers) + " local workers"), std::string::npos) << r.err;
    const auto got = components_of(out + "/store", true);
    ASSERT_EQ(got.size(), reference.size());
    for (const auto& [key, c] : reference) {
      ASSERT_TRUE(got.count(key)) << "component " << key << " missing with " << workers << " workers";
      EXPECT_NEAR(got.at(key).volume, c.volume, 0.005 * std::abs(c.volume) + 1e-9) << key;
      if (!got.at(key).cut) {
        EXPECT_TRUE(got.at(key).manifold) << key;
      }
    }
  }
}

// More workers asked for than the cube has blocks: one per block is started, with a warning that
// says why, and the components are those of the in-process run.
TEST(Workers, MoreWorkersThanBlocksStartOnePerBlock) {
  ScratchDir dir;
  const std::string cube = dir.file("small.raw");
  auto r = run_geotandem("-q synth --kind analytic --shape 40 40 40 --seed 3 --out '" + cube + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string common = "extract '" + cube + "' --iso 0.5 --block-size 32 --out '";
  r = run_geotandem("-q " + common + dir.file("ref") + "' --workers 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_geotandem("--log-level info " + common + dir.file("many") + "' --workers 40");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string warning = "asked for 40 workers, but blocks of 32 cells split this cube into ";
  const std::size_t at = r.err.find(warning);
  ASSERT_NE(at, std::string::npos) << r.err;
  const std::size_t blocks = std::stoul(r.err.substr(at + warning.size()));
  EXPECT_GT(blocks, 1u);
  EXPECT_LT(blocks, 40u);
  EXPECT_NE(r.err.find("blocks: starting " + std::to_string(blocks)), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("extracting with " + std::to_string(blocks) + " local workers"), std::string::npos) << r.err;
  const auto reference = components_of(dir.file("ref"), false), got = components_of(dir.file("many"), false);
  ASSERT_GT(reference.size(), 1u);
  ASSERT_EQ(got.size(), reference.size());
  for (const auto& [key, c] : reference) {
    ASSERT_TRUE(got.count(key)) << "component " << key;
    EXPECT_NEAR(got.at(key).volume, c.volume, 0.005 * std::abs(c.volume) + 1e-9) << key;
  }
  // The run records the workers it started.
  const auto runs = store::ComponentStore::open(dir.file("many")).runs();
  EXPECT_EQ(nlohmann::json::parse(runs.back().parameters).at("workers").get<std::size_t>(), blocks);
}

// Waits until the manager has at least one worker child; empty after the timeout.
std::vector<pid_t> workers_of(pid_t manager, double timeout_s) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < until) {
    auto kids = children_of(manager);
    if (!kids.empty()) return kids;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return {};
}

TEST(Workers, AWorkerKilledAtARandomMomentChangesNothing) {
  Fixture f;
  // How long a run lasts once its workers are there, on this machine today: the moments of the
  // kills are spread over it, so that they land while the run goes on on a fast machine as on a
  // slow one (fixed moments of up to 420 ms missed most runs once a run took 200 ms).
  const pid_t timed = spawn_geotandem(f.extract_args("timed", 2), f.dir.file("timed.log"));
  ASSERT_FALSE(workers_of(timed, 30).empty()) << read_text(f.dir.file("timed.log"));
  const auto started = std::chrono::steady_clock::now();
  ASSERT_EQ(wait_exit(timed, 300), 0) << read_text(f.dir.file("timed.log"));
  // The shortest run seen so far: the timed one may have shared the machine with another test, and a
  // kill run lasts at least as long as a run without a kill once its workers are there.
  double run_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
  std::mt19937 rng(5);
  int killed = 0;
  for (int run = 0; run < 20; ++run) {
    const std::string out = "kill" + std::to_string(run), log = f.dir.file(out + ".log");
    const pid_t manager = spawn_geotandem(f.extract_args(out, 2), log);
    const std::vector<pid_t> workers = workers_of(manager, 30);
    ASSERT_FALSE(workers.empty()) << read_text(log);
    const auto began = std::chrono::steady_clock::now();
    // Spread the moments over the run: extraction of the first blocks, sends and merges, the end.
    const double fraction = 0.02 + 0.8 * static_cast<double>(rng() % 1000) / 1000.0;
    std::this_thread::sleep_for(std::chrono::microseconds(static_cast<std::int64_t>(1000.0 * fraction * run_ms)));
    if (kill(workers[rng() % workers.size()], SIGKILL) == 0) ++killed;
    ASSERT_EQ(wait_exit(manager, 300), 0) << read_text(log);
    run_ms =
        std::min(run_ms, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - began).count());
    f.expect_same(out, run % 5 == 0);
  }
  EXPECT_GT(killed, 10) << "most kills should land while the run is going on (a run took " << run_ms << " ms)";
}

TEST(Workers, AFrozenWorkerIsDetectedByItsHeartbeat) {
  Fixture f;
  const std::string log = f.dir.file("stop.log");
  const pid_t manager = spawn_geotandem(f.extract_args("stop", 2), log);
  const std::vector<pid_t> workers = workers_of(manager, 30);
  ASSERT_FALSE(workers.empty());
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  const bool stopped = kill(workers[0], SIGSTOP) == 0;
  ASSERT_EQ(wait_exit(manager, 300), 0) << read_text(log);
  kill(workers[0], SIGCONT);
  f.expect_same("stop");
  const std::string text = read_text(log);
  if (stopped && text.find("joined; 2 connected") != std::string::npos) {
    EXPECT_NE(text.find("silent"), std::string::npos) << text;
  }
  // The frozen worker, woken and told to stop at the end, was stopped: not an error of the run.
  EXPECT_EQ(text.find("operation cancelled"), std::string::npos) << text;
}

// Lines in the store's record of finished leaves (0 while it does not exist).
std::size_t finished_lines(const std::string& store) {
  const std::string text = read_text(store + "/finished-blocks.txt");
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// The number after `label` in `text` (the first occurrence); -1 when absent.
long number_after(const std::string& text, const std::string& label) {
  const std::size_t at = text.find(label);
  if (at == std::string::npos) return -1;
  return std::strtol(text.c_str() + at + label.size(), nullptr, 10);
}

TEST(Workers, ManagerKilledThenRerunGivesTheSameComponentsOnce) {
  Fixture f;
  const std::string log = f.dir.file("m1.log"), store = f.dir.file("resume");
  const pid_t manager = spawn_geotandem(f.extract_args("resume", 2), log);
  const std::vector<pid_t> workers = workers_of(manager, 30);
  ASSERT_FALSE(workers.empty());
  // Killed once some leaves are finished (their components committed), well before the end.
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (finished_lines(store) < 20 && alive(manager) && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  kill(manager, SIGKILL);
  const std::size_t finished_before = finished_lines(store);
  wait_exit(manager, 10);
  ASSERT_GE(finished_before, 20u) << read_text(log);
  // Local workers end with their manager (the kernel signals them when their parent dies), well
  // before the 10 s of silence after which any worker gives up: an orphan would otherwise keep
  // writing its shard into a store the user may already be copying or checking.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(7);
  for (pid_t w : workers) {
    while (alive(w) && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_FALSE(alive(w)) << "worker " << w << " outlived its manager by 7 s";
  }
  const pid_t again = spawn_geotandem(f.extract_args("resume", 2), f.dir.file("m2.log"));
  ASSERT_EQ(wait_exit(again, 300), 0) << read_text(f.dir.file("m2.log"));
  f.expect_same("resume");
  // The finished leaves were not extracted again: the rerun extracted the others only (none of its
  // workers died, so each of them once).
  const std::string out = read_text(f.dir.file("m2.log"));
  const long skipped = number_after(out, "resumed: ");
  const long extracted = number_after(out, "tasks {\"extract\":");
  ASSERT_GE(skipped, static_cast<long>(finished_before)) << out;
  ASSERT_GE(extracted, 0) << out;
  const long all = number_after(out, "resumed: " + std::to_string(skipped) + " of ");
  EXPECT_EQ(extracted + skipped, all) << out;
  EXPECT_LT(extracted, all) << out;
  // A third run has nothing left to extract.
  const pid_t third = spawn_geotandem(f.extract_args("resume", 2), f.dir.file("m3.log"));
  ASSERT_EQ(wait_exit(third, 300), 0) << read_text(f.dir.file("m3.log"));
  const std::string out3 = read_text(f.dir.file("m3.log"));
  EXPECT_EQ(number_after(out3, "tasks {\"extract\":"), 0) << out3;
  f.expect_same("resume", false);
}

// Sets an environment variable for the processes started while it lives (the test is single-threaded
// when it starts them).
class ScopedEnv {
public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) { setenv(name, value.c_str(), 1); }
  ~ScopedEnv() { unsetenv(name_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
  const char* name_;
};

// Every number after `label` in `text`.
std::vector<long> numbers_after(const std::string& text, const std::string& label) {
  std::vector<long> out;
  for (std::size_t at = text.find(label); at != std::string::npos; at = text.find(label, at + 1))
    out.push_back(std::strtol(text.c_str() + at + label.size(), nullptr, 10));
  return out;
}

// Workers whose jobs have a short walltime retire after their first tasks (their clock starts
// with the process): each tells the manager, hands its surface to another worker (a replacement is
// launched when it retires) and leaves. The run ends with the components of the in-process run,
// and fewer blocks are extracted twice than the retiring workers held (all of which a plain exit
// would have had re-done from the volume). The walltime scales with a plain 2-worker run of the
// same cube (T): a worker retires T/4 after it starts and may wait max(2 s, 2T) for a successor,
// so the test means the same on a fast machine, a loaded one and under a sanitizer.
TEST(Workers, WorkersNearTheirWalltimeHandBackTheirSurfaces) {
  Fixture f;
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t plain = spawn_geotandem(f.extract_args("plain", 2), f.dir.file("plain.log"));
  ASSERT_EQ(wait_exit(plain, 600), 0) << read_text(f.dir.file("plain.log"));
  const double run_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double margin_s = 2 * std::max(2.0, 2 * run_s), walltime_s = margin_s + run_s / 4;
  const std::string log = f.dir.file("walltime.log");
  {
    const ScopedEnv walltime("GEOTANDEM_WALLTIME_SECONDS", std::to_string(walltime_s)),
        margin("GEOTANDEM_WALLTIME_MARGIN_SECONDS", std::to_string(margin_s));
    const pid_t manager = spawn_geotandem(f.extract_args("walltime", 2), log);
    ASSERT_EQ(wait_exit(manager, 900), 0) << read_text(log);
  }
  f.expect_same("walltime");
  const std::string text = read_text(log);
  const std::vector<long> held = numbers_after(text, "it hands back its surface of ");
  ASSERT_GE(held.size(), 2u) << "workers should retire several times: " << text;
  EXPECT_NE(text.find("near its walltime, retires"), std::string::npos) << text;
  const std::vector<long> handed = numbers_after(text, " hands its surface of ");
  ASSERT_FALSE(handed.empty()) << "no retiring worker handed its surface over: " << text;
  for (long n : handed)
    EXPECT_GT(n, 0) << text;
  // Re-extracted blocks: the EXTRACTs beyond one per block, all of them re-done after a give-up
  // or an exit ("will be re-done"), far fewer than the blocks the retiring workers held.
  const long extracted = number_after(text, "tasks {\"extract\":");
  const std::size_t listening = text.find("manager listening on ");
  const long blocks = listening == std::string::npos ? -1 : number_after(text.substr(listening), "; ");
  ASSERT_GT(blocks, 0) << text;
  ASSERT_GE(extracted, blocks) << text;
  long redone = 0, held_at_retirement = 0;
  const std::string redo = " block(s) will be re-done";
  for (std::size_t at = text.find(redo); at != std::string::npos; at = text.find(redo, at + 1)) {
    const std::size_t start = text.find_last_not_of("0123456789", at - 1) + 1;
    redone += std::strtol(text.c_str() + start, nullptr, 10);
  }
  for (long n : held)
    held_at_retirement += n;
  EXPECT_EQ(extracted - blocks, redone) << text;
  EXPECT_LT(extracted - blocks, held_at_retirement) << text;
}

TEST(Workers, InterruptStopsTheWorkersAndLeavesAValidStore) {
  Fixture f;
  const std::string log = f.dir.file("int.log");
  const pid_t manager = spawn_geotandem(f.extract_args("int", 2), log);
  const std::vector<pid_t> workers = workers_of(manager, 30);
  ASSERT_FALSE(workers.empty());
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  kill(manager, SIGINT);
  const int code = wait_exit(manager, 60);
  EXPECT_TRUE(code == 130 || code == 0) << code << read_text(log);
  for (pid_t w : workers)
    EXPECT_FALSE(alive(w)) << "worker " << w << " still runs after Ctrl-C";
  // The store opens, and what it holds is a subset of the reference with the same volumes.
  const auto got = components_of(f.dir.file("int"), false);
  for (const auto& [key, c] : got) {
    ASSERT_TRUE(f.reference.count(key)) << key;
    EXPECT_NEAR(c.volume, f.reference.at(key).volume, 0.005 * std::abs(c.volume) + 1e-9);
  }
  // Rerunning completes it.
  const pid_t again = spawn_geotandem(f.extract_args("int", 2), f.dir.file("int2.log"));
  ASSERT_EQ(wait_exit(again, 300), 0) << read_text(f.dir.file("int2.log"));
  f.expect_same("int");
}

} // namespace
} // namespace geotandem::testing
