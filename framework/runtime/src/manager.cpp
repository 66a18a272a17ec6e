// The manager's event loop (manager.hpp): workers launched and watched, heartbeats, the run from
// start to end. Decisions come from Schedule; the messages are handled in manager_tasks.cpp.
#include <unistd.h>

#include <cmath>
#include <thread>

#include "manager_impl.hpp"

namespace geotandem::runtime {

// Resume: the leaves an earlier run finished are not redone, unless the store holds damaged
// records (which leaves they came from is not known: then everything is redone, and the
// damaged records are written again).
void Manager::Impl::skip_finished_leaves() {
  const std::vector<tandem::NodeId> done = finished.load(log);
  if (done.empty()) return;
  if (const std::uint64_t damaged = committer.count_damaged(cancel)) {
    log.warning(std::to_string(damaged) + " damaged record(s) in the store: every block is extracted again to "
                                          "write them again");
    return;
  }
  for (tandem::NodeId leaf : done)
    schedule.skip(leaf);
  report.skipped_leaves = schedule.skipped();
}

void Manager::Impl::launch_one() {
  std::vector<std::string> argv = options.worker_command;
  const std::string token = new_token();
  argv.insert(argv.end(), {"--connect", endpoint, "--token", token});
  launcher->launch(argv, token);
}

void Manager::Impl::kill_peer(const std::string& token, const std::string& why) {
  auto it = peers.find(token);
  if (it == peers.end()) return;
  Peer& p = it->second;
  const std::vector<tandem::NodeId> redo = schedule.leave(p.id);
  held_triangles -= p.held_triangles;
  relay.forget(token);
  relay.drop_kept([&](TransferId t) { return !schedule.transfer_target(t); });
  log.warning("worker " + token + " (pid " + std::to_string(p.pid) + ") " + why + " during " + task_text(p) + ": " +
              std::to_string(redo.size()) + " block(s) will be re-done from the volume");
  Message f;
  f.kind = MessageKind::finished;
  send(token, f); // a frozen worker that wakes up stops
  dead.insert(token);
  peers.erase(it);
  ++report.deaths;
  report.redone_leaves += redo.size();
  if (launcher && !schedule.complete() && report.restarts < options.max_restarts &&
      peers.size() < std::max<std::size_t>(options.workers, 1)) {
    ++report.restarts;
    launch_one();
  }
}

void Manager::Impl::heartbeats() {
  // Every worker is looked at (ended, silent, overdue, due a heartbeat) at most every 20 ms, not
  // after every batch of messages: with many workers this loop would otherwise cost O(workers)
  // per task.
  const auto now = Clock::now();
  if (now - last_watch < std::chrono::milliseconds(20)) return;
  last_watch = now;
  // Asked before ended(), so that every worker it no longer counts is handled below first.
  const bool exhausted = launcher && peers.empty() && !schedule.complete() && report.restarts >= options.max_restarts &&
                         launcher->running() == 0;
  if (launcher)
    for (const std::string& token : launcher->ended()) {
      if (peers.count(token)) {
        kill_peer(token, "ended");
      } else if (!dead.count(token)) { // never said HELLO
        dead.insert(token);
        if (report.restarts >= options.max_restarts)
          throw Error("worker " + token + " exited before connecting, and " + std::to_string(report.restarts) +
                          " replacements were already started",
                      {.worker = token}, "run 'geotandem worker --help' to check the installation; see the log above");
        log.warning("worker " + token + " exited before connecting; starting another");
        ++report.restarts;
        launch_one();
      }
    }
  // Every worker died and no replacement may start: nothing can connect any more, and waiting out
  // the connect timeout (half an hour under a scheduler) would only delay this error.
  if (exhausted && peers.empty())
    throw Error("every worker died, and the limit of " + std::to_string(options.max_restarts) +
                    " replacement workers is reached",
                {},
                "see the log above for why each worker died; the finished blocks are in the store, and a rerun "
                "of the same command resumes from them");
  std::vector<std::string> silent;
  for (auto& [token, p] : peers)
    if (now - p.heard > options.lease) silent.push_back(token);
  for (const std::string& token : silent)
    kill_peer(token, "has been silent for " + std::to_string(options.lease.count() / 1000.0).substr(0, 4) + " s");
  overdue_tasks();
  if (now - last_beat >= options.heartbeat) {
    Message h;
    h.kind = MessageKind::heartbeat;
    for (auto& [token, p] : peers)
      send(token, h);
    last_beat = now;
  }
}

// A live worker (it heartbeats) that never finishes its task, or never asks for one after its
// SETUP, would hold the run forever: past the task bound it is treated as dead. Its leaves are
// re-done under new leases, and what it sends later is ignored (it is told FINISHED).
void Manager::Impl::overdue_tasks() {
  const auto now = Clock::now();
  const Clock::duration bound = task_bound();
  std::vector<std::pair<std::string, std::string>> overdue;
  for (const auto& [token, p] : peers) {
    const bool stuck = p.task ? now - p.task_start > bound : !p.asked && now - p.joined > bound;
    if (!stuck) continue;
    const auto seconds = std::llround(std::chrono::duration<double>(bound).count());
    overdue.emplace_back(token, (p.task ? "has not finished its task within " : "has not asked for a task within ") +
                                    std::to_string(seconds) +
                                    " s (the task bound: GEOTANDEM_TASK_TIMEOUT_SECONDS, or 10 times the "
                                    "longest task so far)");
  }
  for (const auto& [token, why] : overdue)
    kill_peer(token, why);
}

void Manager::Impl::stop_workers() {
  Message f;
  f.kind = MessageKind::finished;
  for (auto& [token, p] : peers)
    send(token, f);
  if (launcher) launcher->stop_all(5.0);
}

ManagerReport Manager::Impl::run() {
  start = Clock::now();
  cpu_at_start = cpu_seconds();
  skip_finished_leaves();
  progress.begin("extraction, " + std::to_string(report.leaves) + " blocks", report.leaves + 1, "blocks+final");
  if (report.skipped_leaves > 0) {
    log.info("resuming: " + std::to_string(report.skipped_leaves) + " of " + std::to_string(report.leaves) +
             " blocks were finished by an earlier run (their components are in the store) and are not redone");
    for (std::size_t i = 0; i < report.skipped_leaves; ++i)
      advance();
  }
  if (launcher)
    for (std::size_t i = 0; i < options.workers; ++i)
      launch_one();
  log.info("manager listening on " + endpoint + "; " + std::to_string(report.leaves) + " blocks of at most " +
           std::to_string(tree.leaf_size()) + " cells");
  Clock::time_point alone = Clock::now(); // since when no worker is connected
  std::optional<Clock::time_point> completed;
  try {
    for (;;) {
      cancel.throw_if_cancelled();
      socket.receive(
          // Once the run is complete it only waits for workers to leave: it looks more often.
          std::chrono::milliseconds(completed ? 5 : 100),
          [this](const std::string& token, std::span<const std::byte> body) { handle(token, body); },
          [this](const std::string& why) { drop(why); });
      heartbeats();
      if (Clock::now() - last_record > std::chrono::milliseconds(100)) record_finished();
      commits.rethrow_failure();
      if (schedule.complete()) {
        if (!completed) completed = Clock::now();
        // Each is told FINISHED when it asks (or says HELLO, if it starts late).
        const bool all_gone = peers.empty() && (!launcher || launcher->running() == 0);
        if (all_gone || since(*completed) > 3.0) break;
      }
      if (!peers.empty()) alone = Clock::now();
      if (peers.empty() && Clock::now() - alone > options.connect_timeout)
        throw Error("no worker connected to " + endpoint + " within " +
                        std::to_string(options.connect_timeout.count() / 1000) + " s",
                    {},
                    report.workers ? "every worker died: see the log above"
                                   : "check that workers can start and reach this address (firewall, --bind)");
    }
  } catch (...) {
    relay.close(); // a rerun redoes unmerged surfaces from the volume
    stop_workers();
    progress.stop();
    record_finished();
    const bool failed_before = commits.failed(); // then that failure is what goes up
    try {
      commits.drain(); // what the workers committed stays committed
    } catch (const std::exception& e) {
      if (!failed_before) log.error(std::string("the index could not take the last commits: ") + e.what());
    }
    throw;
  }
  // Workers told FINISHED exit by themselves; those still running after a grace are stopped.
  report.seconds = since(start);
  const auto grace = Clock::now() + std::chrono::seconds(3);
  while (launcher && launcher->running() > 0 && Clock::now() < grace)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  stop_workers();
  progress.end();
  record_finished();
  commits.drain();
  report.manager_cpu_seconds = cpu_seconds() - cpu_at_start;
  report.messages_in = messages_in;
  report.messages_out = messages_out;
  report.commit_seconds = commits.busy_seconds();
  {
    TaskLogRun totals;
    totals.manager_cpu_seconds = report.manager_cpu_seconds;
    totals.wall_seconds = report.seconds;
    totals.messages_in = messages_in;
    totals.messages_out = messages_out;
    totals.rows = rows_in;
    totals.commit_seconds = report.commit_seconds;
    totals.workers = report.workers;
    totals.commit_cpu_seconds = commits.cpu_seconds();
    task_log.close(totals);
  }
  report.components = committer.added();
  report.duplicates = committer.duplicates();
  report.repaired = committer.repaired();
  report.repaired_keys = committer.repaired_keys();
  report.bytes_in = socket.bytes_in();
  report.bytes_out = socket.bytes_out();
  report.manager_peak_rss_kb = peak_rss_kb(); // of the whole process, so far
  relay.close();
  report.relay_peak_held = relay.usage().peak_held;
  report.relay_spilled = relay.usage().spilled;
  report.relay_spilled_bytes = relay.usage().spilled_bytes;
  if (report.relay_spilled > 0)
    log.info(std::to_string(report.relay_spilled) + " partial surface(s), " +
             std::to_string(report.relay_spilled_bytes >> 20) + " MiB, waited for their merge in " +
             relay.spill_dir().string() + " (past the relay's " + std::to_string(options.relay_memory >> 20) +
             " MiB in memory)");

  return report;
}

Manager::Manager(ManagerOptions options, store::ComponentStore& store, Launcher* launcher, Logger& log,
                 Progress& progress, const CancelToken& cancel)
    : impl_(std::make_unique<Impl>(std::move(options), store, launcher, log, progress, cancel)) {}
Manager::~Manager() = default;
const std::string& Manager::endpoint() const {
  return impl_->endpoint;
}
std::string Manager::new_token() {
  return impl_->new_token();
}
ManagerReport Manager::run() {
  return impl_->run();
}

} // namespace geotandem::runtime
