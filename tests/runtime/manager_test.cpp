// The manager as a library with real sockets: no worker, workers that cannot start, garbage sent
// to its socket while real worker processes extract, surfaces in small chunks, on disk and over
// the size cap, workers dead past the restart limit. manager_trust_test.cpp: a task held forever,
// a reconnecting worker, the run's key directory.
#include <cstdlib>

#include "manager_run.hpp"

namespace geotandem::runtime {
namespace {

using namespace testing_manager;

TEST(Manager, NoWorkerWithinTheTimeoutIsAClearError) {
  ManagerRun run;
  run.options.connect_timeout = std::chrono::milliseconds(800);
  Manager manager(run.options, *run.store, nullptr, Logger::null(), run.progress, run.cancel);
  const std::string text = message_of([&] { manager.run(); });
  EXPECT_NE(text.find("no worker connected to tcp://127.0.0.1:"), std::string::npos) << text;
}

TEST(Manager, WorkersThatCannotStartEndTheRunWithAClearError) {
  ManagerRun run;
  run.options.worker_command = {"/bin/false"};
  run.options.max_restarts = 2;
  LocalLauncher launcher;
  Manager manager(run.options, *run.store, &launcher, Logger::null(), run.progress, run.cancel);
  const std::string text = message_of([&] { manager.run(); });
  EXPECT_NE(text.find("exited before connecting"), std::string::npos) << text;
  EXPECT_EQ(launcher.running(), 0u);
}

TEST(Manager, AWorkerThatCannotOpenTheInputEndsTheRunWithItsReason) {
  ManagerRun run;
  run.options.settings.volume = R"({"kind":"file","path":"/nonexistent/cube.raw","nan":"error","variable":""})";
  LocalLauncher launcher;
  Manager manager(run.options, *run.store, &launcher, Logger::null(), run.progress, run.cancel);
  const std::string text = message_of([&] { manager.run(); });
  EXPECT_NE(text.find("could not start"), std::string::npos) << text;
  EXPECT_NE(text.find("/nonexistent/cube.raw"), std::string::npos) << text;
}

// A worker started by hand (as a cluster scheduler would) joins a run that one local worker began,
// and takes part: the run ends with the components of the in-process extraction.
TEST(Manager, AWorkerJoiningLateTakesPart) {
  // Large enough that the run is still going when the late worker has started, on a loaded
  // machine too (a worker saying HELLO after the end is told FINISHED without joining).
  ManagerRun run("64 60 56");
  ASSERT_TRUE(run.extract_reference());
  run.options.workers = 1;
  // One leaf per EXTRACT: with batches the first worker finished the 512 leaves before the late one
  // said HELLO on an idle machine (on main too), and the late worker then waited for a manager gone.
  setenv("GEOTANDEM_EXTRACT_BATCH", "1", 1);
  struct Unset {
    ~Unset() { unsetenv("GEOTANDEM_EXTRACT_BATCH"); }
  } unset;
  LocalLauncher launcher;
  Logger log(std::cerr, LogLevel::info);
  Manager manager(run.options, *run.store, &launcher, log, run.progress, run.cancel);
  const std::string token = manager.new_token();
  const std::string endpoint = manager.endpoint();
  pid_t late = 0;
  std::thread starter([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    late =
        testing::spawn_geotandem({"-q", "worker", "--connect", endpoint, "--token", token}, run.dir.file("late.log"));
  });
  ManagerReport report;
  EXPECT_NO_THROW(report = manager.run());
  starter.join();
  const int code = testing::wait_exit(late, 60);
  EXPECT_EQ(code, 0) << testing::read_text(run.dir.file("late.log"));
  EXPECT_EQ(report.workers, 2u) << "the late worker did not join";
  run.expect_reference_components(false);
}

// Random bytes, truncated and damaged messages, oversized claims, replayed task results and HELLOs
// under unknown tokens, sent from several peers that hold the run's keys (a broken worker: what
// passes the authentication must still be checked) and one that does not (refused before any of
// its frames reaches the manager) while two real workers run.
void send_garbage(const std::string& endpoint, std::atomic<bool>& stop, std::atomic<int>& sent) {
  zmq::context_t context(1);
  std::mt19937 rng(17);
  std::vector<zmq::socket_t> peers;
  for (int i = 0; i < 5; ++i) {
    peers.emplace_back(context, zmq::socket_type::dealer);
    peers.back().set(zmq::sockopt::linger, 0);
    if (i > 0) peers.back().set(zmq::sockopt::routing_id, "w-impostor-" + std::to_string(i));
    if (i < 4) use_worker_keys(peers.back());
    peers.back().connect(endpoint);
  }
  Message done;
  done.kind = MessageKind::done;
  done.lease = {1, 1};
  const std::vector<std::byte> valid = encode(done);
  while (!stop) {
    zmq::socket_t& s = peers[rng() % peers.size()];
    std::vector<std::byte> frame;
    switch (rng() % 6) {
    case 0:
      frame.resize(rng() % 300);
      for (auto& b : frame)
        b = static_cast<std::byte>(rng());
      break;
    case 1: frame.assign(valid.begin(), valid.begin() + static_cast<long>(rng() % valid.size())); break;
    case 2:
      frame = valid;
      frame[rng() % frame.size()] ^= std::byte{0x40};
      break;
    case 3: { // a header announcing 4 GiB
      frame = valid;
      const std::uint32_t huge = 0xffffffffu;
      std::memcpy(frame.data() + 8, &huge, 4);
      break;
    }
    case 4: frame = valid; break; // a replayed result from a peer that holds no lease
    case 5: {
      Message hello;
      hello.kind = MessageKind::hello;
      hello.text = "w-impostor";
      frame = encode(hello);
      break;
    }
    }
    (void)s.send(zmq::buffer(frame.data(), frame.size()), zmq::send_flags::dontwait);
    if (rng() % 4 == 0) // and a multi-frame message
      (void)s.send(zmq::str_buffer("x"), zmq::send_flags::sndmore | zmq::send_flags::dontwait),
          (void)s.send(zmq::str_buffer("y"), zmq::send_flags::dontwait);
    ++sent;
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
}

TEST(Manager, GarbageOnItsSocketIsDroppedAndTheRunCompletes) {
  ManagerRun run("48 44 40");
  ASSERT_TRUE(run.extract_reference());
  run.options.workers = 2;
  LocalLauncher launcher;
  Manager manager(run.options, *run.store, &launcher, Logger::null(), run.progress, run.cancel);
  std::atomic<bool> stop{false};
  std::atomic<int> sent{0};
  std::thread garbage(send_garbage, manager.endpoint(), std::ref(stop), std::ref(sent));
  ManagerReport report;
  EXPECT_NO_THROW(report = manager.run());
  stop = true;
  garbage.join();
  EXPECT_GT(sent.load(), 50);
  EXPECT_GT(report.dropped_messages, 0u);
  run.expect_reference_components(false);
}

// Partial surfaces of a few KiB cut into chunks of 256 bytes: every SEND and MERGE runs many
// windows of credits through the manager, and the result is the in-process one.
TEST(Manager, SurfacesInSmallChunksUnderCreditsGiveTheSameComponents) {
  ManagerRun run("48 44 40");
  ASSERT_TRUE(run.extract_reference());
  run.options.workers = 2;
  run.options.settings.chunk_bytes = 256;
  std::string text;
  const std::optional<ManagerReport> report = run.run_manager(LogLevel::debug, text);
  ASSERT_TRUE(report) << text;
  EXPECT_GT(report->largest_surface, 256u * kChunkWindow) << "no surface needed more than one window of credits";
  EXPECT_EQ(report->dropped_messages, 0u) << text;
  EXPECT_EQ(report->deaths, 0u) << text;
  run.expect_reference_components(true);
}

// A relay budget of 0 bytes: every partial surface waits for its merge in a file beside the store,
// and the run ends with the in-process components and no file left.
TEST(Manager, SurfacesWaitingOnDiskPastTheRelayBudgetGiveTheSameComponents) {
  ManagerRun run("48 44 40");
  ASSERT_TRUE(run.extract_reference());
  run.options.workers = 2;
  run.options.relay_memory = 0;
  std::string text;
  const std::optional<ManagerReport> report = run.run_manager(LogLevel::info, text);
  ASSERT_TRUE(report) << text;
  EXPECT_GT(report->merge, 0u);
  EXPECT_EQ(report->relay_spilled, report->merge) << "a surface was merged without waiting on disk";
  EXPECT_EQ(report->relay_peak_held, 0u);
  EXPECT_GT(report->relay_spilled_bytes, 0u);
  EXPECT_NE(text.find("waited for their merge in " + run.dir.file("store.relay")), std::string::npos) << text;
  EXPECT_FALSE(std::filesystem::exists(run.dir.file("store.relay"))) << "the relay's files outlived the run";
  EXPECT_EQ(report->deaths, 0u) << text;
  run.expect_reference_components(true);
}

// A size cap below the surfaces: each oversized SEND is logged and dropped, its worker is taken
// for faulty and replaced; the run ends (the last worker standing may finish alone, or no worker
// is left: a clear error) instead of crashing or hanging.
TEST(Manager, SurfacesOverTheSizeCapAreDroppedNotACrash) {
  ManagerRun run("48 44 40");
  run.options.workers = 2;
  run.options.max_restarts = 2;
  run.options.max_surface = 2048;
  run.options.settings.chunk_bytes = 512;
  LocalLauncher launcher;
  std::ostringstream text;
  Logger log(text, LogLevel::info);
  Manager manager(run.options, *run.store, &launcher, log, run.progress, run.cancel);
  const std::string error = message_of([&] { manager.run(); });
  EXPECT_NE(text.str().find("past the cap of 2048 bytes"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("sent a damaged partial surface"), std::string::npos) << text.str();
  if (!error.empty()) {
    EXPECT_NE(error.find("every worker died"), std::string::npos) << error;
  }
  EXPECT_EQ(launcher.running(), 0u);
}

// Once the last worker died and no replacement may start, the run ends with that reason at
// once; before, it waited out the connect timeout (half an hour under a scheduler) and then
// blamed the network.
// The cube is one leaf, whose extraction takes far longer than the manager's 100 ms poll: a worker
// that answered every poll within the 1 ms lease would never be found silent (with many small
// leaves, a lone fast worker did just that and finished the run).
TEST(Manager, WorkersDeadPastTheRestartLimitEndTheRunAtOnceSayingWhy) {
  ManagerRun run("192 176 160");
  run.options.settings.extraction.block_size = 256;
  run.options.workers = 2;
  run.options.max_restarts = 1;
  run.options.lease = std::chrono::milliseconds(1); // each worker is soon found silent, and dropped
  run.options.connect_timeout = std::chrono::minutes(30);
  LocalLauncher launcher;
  std::ostringstream text;
  Logger log(text, LogLevel::info);
  Manager manager(run.options, *run.store, &launcher, log, run.progress, run.cancel);
  const std::string error = message_of([&] { manager.run(); });
  EXPECT_NE(error.find("every worker died, and the limit of 1 replacement workers is reached"), std::string::npos)
      << error << "\n"
      << text.str();
  EXPECT_NE(error.find("a rerun of the same command resumes"), std::string::npos) << error;
  EXPECT_NE(text.str().find("has been silent"), std::string::npos) << text.str();
  EXPECT_EQ(launcher.running(), 0u);
}

} // namespace
} // namespace geotandem::runtime
