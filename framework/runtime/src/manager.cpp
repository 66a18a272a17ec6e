// The manager's event loop (manager.hpp). Decisions come from Schedule; this file moves messages.
#include "geotandem/runtime/manager.hpp"

#include <unistd.h>

#include <algorithm>
#include <map>
#include <set>
#include <thread>

#include "commit_queue.hpp"
#include "component_committer.hpp"
#include "finished_blocks.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/runtime/schedule.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "manager_socket.hpp"
#include "manager_support.hpp"
#include "surface_relay.hpp"
#include "worker_failure.hpp"

namespace geotandem::runtime {

using detail::Clock;
using detail::cpu_seconds;
using detail::peak_rss_kb;
using detail::random_hex;
using detail::since;

struct Manager::Impl {
  struct Peer {
    WorkerId id = 0;
    std::string token;
    std::uint64_t pid = 0;
    Clock::time_point heard;
    Lease lease; // of the task in progress
    std::optional<Decision> task;
    Clock::time_point task_start;
    std::uint64_t tasks = 0;
  };

  ManagerOptions options;
  store::ComponentStore& store;
  Launcher* launcher;
  Logger& log;
  Progress& progress;
  const CancelToken& cancel;
  detail::ManagerSocket socket;
  const std::string& endpoint = socket.endpoint();
  detail::ComponentCommitter committer{store};
  std::string run_prefix = random_hex(6);
  std::size_t token_count = 0;
  std::set<std::string> allowed, dead, departed; // departed: told FINISHED after its work, a subset of dead
  std::map<std::string, Peer> peers;             // by token
  tandem::BlockTree tree;
  Schedule schedule{tree};
  detail::FinishedBlocks finished{store.directory(), tree};
  detail::CommitQueue commits{committer}; // after what its thread uses
  detail::SurfaceRelay relay{options.max_surface, static_cast<std::size_t>(options.settings.chunk_bytes)};
  std::map<tandem::NodeId, std::uint32_t> attempts;
  std::uint64_t next_task = 1;
  WorkerId next_worker = 1;
  ManagerReport report;
  Clock::time_point start = Clock::now(), last_beat = Clock::now();
  double cpu_at_start = cpu_seconds();
  std::uint64_t progress_done = 0;

  Impl(ManagerOptions o, store::ComponentStore& s, Launcher* l, Logger& lg, Progress& p, const CancelToken& c)
      : options(std::move(o)), store(s), launcher(l), log(lg), progress(p), cancel(c),
        socket(options.bind, options.max_message, s.directory().string() + ".keys", lg),
        tree(tandem::cube_cells(s.geometry().shape), std::max<std::int64_t>(options.settings.block_size, 8)) {
    report.leaves = tree.leaves().size();
  }

  // Resume: the leaves an earlier run finished are not redone, unless the store holds damaged
  // records (which leaves they came from is not known: then everything is redone, and the
  // damaged records are written again).
  void skip_finished_leaves() {
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

  std::string new_token() {
    std::string t = "w" + run_prefix + "-" + std::to_string(++token_count);
    allowed.insert(t);
    return t;
  }

  void launch_one() {
    std::vector<std::string> argv = options.worker_command;
    const std::string token = new_token();
    argv.insert(argv.end(), {"--connect", endpoint, "--token", token});
    launcher->launch(argv, token);
  }

  bool send(const std::string& token, const Message& m) { return socket.send(token, encode(m)); }

  void drop(const std::string& why) {
    ++report.dropped_messages;
    if (report.dropped_messages <= 20) log.warning("dropped a message: " + why);
    if (report.dropped_messages == 20) log.warning("further dropped messages are not logged");
  }

  std::string task_text(const Peer& p) const {
    if (!p.task) return "no task";
    std::string t = to_string(p.task->kind);
    if (p.task->kind == TaskKind::extract) t += " of " + tree.describe(p.task->leaf);
    return t;
  }

  void kill_peer(const std::string& token, const std::string& why) {
    auto it = peers.find(token);
    if (it == peers.end()) return;
    Peer& p = it->second;
    const std::vector<tandem::NodeId> redo = schedule.leave(p.id);
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

  // Workers launched that have not said HELLO yet (nor ended).
  std::size_t workers_to_come() const { return allowed.size() - peers.size() - dead.size(); }

  std::string token_of(WorkerId id) const {
    for (const auto& [token, p] : peers)
      if (p.id == id) return token;
    return "?";
  }

  // RETIRE: the worker is near its walltime. It gets no more EXTRACT and hands its surface to
  // another worker (Schedule); a replacement with a fresh walltime is launched now, so that it can
  // take the surface. Not counted against max_restarts: a retiring worker loses nothing.
  void retire(Peer& p, const std::string& why) {
    if (!schedule.retiring(p.id)) {
      schedule.retire(p.id);
      ++report.retirements;
      log.info("worker " + p.token + " retires (" + why + "); it hands back its surface of " +
               std::to_string(schedule.leaves_held(p.id)) + " block(s)");
      std::size_t staying = workers_to_come();
      for (const auto& [token, q] : peers)
        staying += schedule.retiring(q.id) ? 0 : 1;
      if (launcher && !schedule.complete() && staying < std::max<std::size_t>(options.workers, 1)) launch_one();
    }
    decide(p);
  }

  void decide(Peer& p) {
    schedule.expect_joins(workers_to_come());
    const Decision d = schedule.next(p.id);
    if (d.kind == TaskKind::send && schedule.retiring(p.id)) {
      report.handed_back += schedule.transfer_leaves(d.transfer);
      log.info("worker " + p.token + " hands its surface of " + std::to_string(schedule.transfer_leaves(d.transfer)) +
               " block(s) to worker " + token_of(d.target));
    }
    if (d.kind == TaskKind::finished && !d.final && schedule.leaves_held(p.id) > 0) {
      const std::size_t n = schedule.leaves_held(p.id);
      log.warning("worker " + p.token + " retires with no worker to take its surface: " + std::to_string(n) +
                  " block(s) will be re-done from the volume");
      report.redone_leaves += n;
    }
    Message m = detail::task_message(d, tree);
    if (d.kind == TaskKind::extract) m.lease.attempt = ++attempts[d.leaf];
    const bool busy = d.kind != TaskKind::wait && (d.kind != TaskKind::finished || d.final);
    if (busy) {
      m.lease.task = next_task++;
      p.lease = m.lease;
      p.task = d;
      p.task_start = Clock::now();
      log.debug("worker " + p.token + ": " + task_text(p));
    }
    if (d.kind == TaskKind::merge) {
      const detail::SurfaceRelay::Header h = relay.begin_outbound(p.token, d.transfer);
      m.number = h.total;
      m.box[0] = static_cast<std::int64_t>(h.checksum);
    }
    if (d.kind == TaskKind::send) relay.begin_inbound(p.token);
    if (!send(p.token, m)) return kill_peer(p.token, "cannot be reached");
    if (d.kind == TaskKind::merge) pump(p, 0);
    if (d.kind == TaskKind::finished && !d.final) depart(p.token);
  }

  // The chunks of the MERGE in progress that the worker's credits allow now.
  void pump(Peer& p, std::uint64_t credits) {
    relay.pump(p.token, credits, [&](std::uint64_t offset, std::span<const std::byte> piece) {
      Message c;
      c.kind = MessageKind::merge_chunk;
      c.lease = p.lease;
      c.number = offset;
      c.bytes.assign(piece.begin(), piece.end());
      send(p.token, c);
    });
  }

  // A worker told to stop leaves the run without a warning.
  void depart(const std::string& token) {
    auto it = peers.find(token);
    if (it == peers.end()) return;
    log.info("worker " + token + " done after " + std::to_string(it->second.tasks) + " task(s)");
    schedule.leave(it->second.id);
    relay.forget(token);
    dead.insert(token);
    departed.insert(token);
    peers.erase(it);
  }

  // The bar counts blocks extracted and the final pass; a re-done block does not move it twice.
  void advance() {
    if (progress_done < report.leaves + 1) progress.advance();
    ++progress_done;
  }

  void task_done(Peer& p, const Message& m) {
    const double s = static_cast<double>(m.number) / 1000.0;
    report.worker_peak_rss_kb = std::max(report.worker_peak_rss_kb, m.box[0]);
    switch (p.task->kind) {
    case TaskKind::extract: ++report.extract, report.seconds_extract += s, advance(); break;
    case TaskKind::merge: ++report.merge, report.seconds_merge += s; break;
    case TaskKind::finished:
      ++report.finish, report.seconds_finish += s, advance();
      report.input_triangles = static_cast<std::uint64_t>(m.box[2]);
      report.collapses = static_cast<std::uint64_t>(m.box[3]);
      break;
    default: break;
    }
    ++p.tasks;
    // An empty surface: its leaves' components are all committed (the COMMIT came first).
    if (m.box[1] == 1) {
      const std::vector<tandem::NodeId> leaves = schedule.held(p.id);
      log.debug("worker " + p.token + ": surface empty after " + task_text(p) + "; " + std::to_string(leaves.size()) +
                " leaves finished");
      commits.then([this, leaves] { finished.record(leaves); }); // once their COMMITs are in the index
    }
    const bool final = p.task->kind == TaskKind::finished;
    p.task.reset();
    schedule.done(p.id);
    if (final) depart(p.token);
  }

  void handle(const std::string& token, std::span<const std::byte> frame) {
    if (dead.count(token)) { // a frozen worker woke up, or a late message of one that left
      Message f;
      f.kind = MessageKind::finished;
      send(token, f);
      // A worker told FINISHED may still have had a heartbeat on its way: that is not a dropped
      // message. One declared dead that speaks again is.
      if (!departed.count(token)) ++report.dropped_messages;
      return;
    }
    if (!allowed.count(token)) return drop("from an unknown sender (not a token this manager issued)");
    Message m;
    try {
      m = decode(frame, options.max_message);
    } catch (const ProtocolError& e) {
      return drop(std::string("from worker ") + token + ": " + e.what());
    }
    auto it = peers.find(token);
    if (m.kind == MessageKind::hello) {
      if (it != peers.end()) return drop("a second HELLO from worker " + token);
      if (schedule.complete()) { // a late starter: nothing left to do
        Message f;
        f.kind = MessageKind::finished;
        send(token, f);
        dead.insert(token);
        departed.insert(token);
        return;
      }
      Peer p{.id = next_worker++, .token = token, .pid = m.number, .heard = Clock::now()};
      schedule.join(p.id);
      ++report.workers;
      log.info("worker " + token + " (pid " + std::to_string(p.pid) + ") joined; " + std::to_string(peers.size() + 1) +
               " connected");
      Message s;
      s.kind = MessageKind::setup;
      s.text = options.settings.to_json();
      peers.emplace(token, p);
      if (!send(token, s)) kill_peer(token, "cannot be reached");
      return;
    }
    if (it == peers.end()) return drop(std::string(to_string(m.kind)) + " from worker " + token + " before its HELLO");
    Peer& p = it->second;
    p.heard = Clock::now();
    switch (m.kind) {
    case MessageKind::heartbeat: return;
    case MessageKind::ask:
      if (p.task) { // it lost its task (a message dropped on the way): its work is re-done elsewhere
        drop("ASK from worker " + token + " while it has a task (" + task_text(p) + ")");
        return kill_peer(token, "asked again without finishing its task");
      }
      return decide(p);
    case MessageKind::retire:
      if (p.task) {
        drop("RETIRE from worker " + token + " while it has a task (" + task_text(p) + ")");
        return kill_peer(token, "retired without finishing its task");
      }
      return retire(p, m.text);
    case MessageKind::failed:
      if (!p.task && m.lease == Lease{}) // SETUP failed: every worker would fail the same way
        detail::throw_worker_failure(static_cast<int>(m.number), "could not start: " + m.text, token,
                                     "every worker reads the input itself: check that it is readable and "
                                     "intact from every worker, and that the store directory is writable");
      if (!p.task || !(m.lease == p.lease)) return drop("a stale FAILED from worker " + token);
      detail::throw_worker_failure(static_cast<int>(m.number), "failed during " + task_text(p) + ": " + m.text, token,
                                   "fix the cause and rerun the same command: committed components are kept");
    default: break;
    }
    if (!p.task || !(m.lease == p.lease))
      return drop(std::string(to_string(m.kind)) + " from worker " + token + " with a stale lease (task " +
                  std::to_string(m.lease.task) + ", attempt " + std::to_string(m.lease.attempt) + ")");
    switch (m.kind) {
    case MessageKind::commit: commits.commit(std::move(m.entries)); return;
    case MessageKind::surface_chunk: {
      if (p.task->kind != TaskKind::send) return drop("a surface chunk from worker " + token + " outside a SEND");
      if (const std::optional<std::string> why = relay.chunk_in(token, m.number, m.bytes)) {
        drop("from worker " + token + ": " + *why); // its surface cannot arrive whole: its leaves are redone
        return kill_peer(token, "sent a damaged partial surface");
      }
      Message credit;
      credit.kind = MessageKind::surface_credit;
      credit.lease = m.lease;
      credit.number = 1;
      send(token, credit);
      return;
    }
    case MessageKind::merge_credit:
      if (p.task->kind != TaskKind::merge) return drop("a merge credit from worker " + token + " outside a MERGE");
      return pump(p, m.number);
    case MessageKind::surface: {
      if (p.task->kind != TaskKind::send) return drop("SURFACE from worker " + token + " outside a SEND");
      const TransferId t = p.task->transfer;
      std::uint64_t bytes = 0;
      if (const std::optional<std::string> why =
              relay.end_inbound(token, m.number, static_cast<std::uint64_t>(m.box[0]), bytes)) {
        drop("from worker " + token + ": " + *why);
        return kill_peer(token, "sent a damaged partial surface");
      }
      report.surface_bytes += bytes;
      report.largest_surface = std::max<std::uint64_t>(report.largest_surface, bytes);
      ++report.send;
      ++p.tasks;
      p.task.reset();
      if (schedule.arrived(p.id, t)) relay.keep(token, t);
      relay.forget(token);
      return;
    }
    case MessageKind::done:
      if (p.task->kind == TaskKind::send) return drop("DONE from worker " + token + " for a SEND");
      return task_done(p, m);
    default: return drop(std::string("unexpected ") + to_string(m.kind) + " from worker " + token);
    }
  }

  void heartbeats() {
    if (launcher)
      for (const std::string& token : launcher->ended()) {
        if (peers.count(token)) {
          kill_peer(token, "ended");
        } else if (!dead.count(token)) { // never said HELLO
          dead.insert(token);
          if (report.restarts >= options.max_restarts)
            throw Error("worker " + token + " exited before connecting, and " + std::to_string(report.restarts) +
                            " replacements were already started",
                        {.worker = token},
                        "run 'geotandem worker --help' to check the installation; see the log above");
          log.warning("worker " + token + " exited before connecting; starting another");
          ++report.restarts;
          launch_one();
        }
      }
    const auto now = Clock::now();
    std::vector<std::string> silent;
    for (auto& [token, p] : peers)
      if (now - p.heard > options.lease) silent.push_back(token);
    for (const std::string& token : silent)
      kill_peer(token, "has been silent for " + std::to_string(options.lease.count() / 1000.0).substr(0, 4) + " s");
    if (now - last_beat >= options.heartbeat) {
      Message h;
      h.kind = MessageKind::heartbeat;
      for (auto& [token, p] : peers)
        send(token, h);
      last_beat = now;
    }
  }

  void stop_workers() {
    Message f;
    f.kind = MessageKind::finished;
    for (auto& [token, p] : peers)
      send(token, f);
    if (launcher) launcher->stop_all(5.0);
  }

  ManagerReport run() {
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
      stop_workers();
      progress.end();
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
    commits.drain();
    report.manager_cpu_seconds = cpu_seconds() - cpu_at_start;
    report.components = committer.added();
    report.duplicates = committer.duplicates();
    report.repaired = committer.repaired();
    report.bytes_in = socket.bytes_in();
    report.bytes_out = socket.bytes_out();
    report.manager_peak_rss_kb = peak_rss_kb(); // of the whole process, so far

    return report;
  }
};

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
