#pragma once
// The manager's state (manager.hpp): the members the event loop (manager.cpp) and the message
// handling (manager_tasks.cpp) share. Internal to the runtime.
#include "geotandem/runtime/manager.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <thread>

#include "batch_extract.hpp"
#include "commit_queue.hpp"
#include "component_committer.hpp"
#include "finished_blocks.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/runtime/schedule.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "manager_socket.hpp"
#include "manager_support.hpp"
#include "surface_relay.hpp"
#include "task_log.hpp"
#include "worker_failure.hpp"

namespace geotandem::runtime {

using detail::Clock;
using detail::cpu_seconds;
using detail::peak_rss_kb;
using detail::random_hex;
using detail::since;

// A path next to `dir` (a store): its name with `suffix` appended, a trailing slash or not.
inline std::filesystem::path beside(std::filesystem::path dir, const std::string& suffix) {
  if (!dir.has_filename()) dir = dir.parent_path();
  dir += suffix;
  return dir;
}

struct Manager::Impl {
  struct Peer {
    WorkerId id = 0;
    std::string token;
    std::uint64_t pid = 0;
    Clock::time_point heard;
    Clock::time_point joined;
    bool asked = false; // it asked for a task (or retired) since SETUP
    Lease lease;        // of the task in progress
    std::optional<Decision> task;
    Clock::time_point task_start;
    std::uint64_t task_bytes = 0, task_rows = 0; // of the task in progress, for the task log
    std::uint64_t tasks = 0;
    std::uint64_t held_triangles = 0; // its surface's, after its last task
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
  detail::TaskLogWriter task_log{store.directory() / kTaskLogName, tree.cube(), tree.leaf_size(),
                                 detail::extract_batch_cap(), std::thread::hardware_concurrency()};
  std::uint64_t messages_in = 0, messages_out = 0, rows_in = 0;
  detail::CommitQueue commits{committer}; // after what its thread uses
  detail::SurfaceRelay relay{options.max_surface, static_cast<std::size_t>(options.settings.chunk_bytes),
                             options.relay_memory, beside(store.directory(), ".relay")};
  std::map<tandem::NodeId, std::uint32_t> attempts;
  std::uint64_t next_task = 1;
  WorkerId next_worker = 1;
  ManagerReport report;
  Clock::time_point start = Clock::now(), last_beat = Clock::now();
  double cpu_at_start = cpu_seconds();
  std::uint64_t progress_done = 0;
  std::uint64_t held_triangles = 0; // the sum of the peers' held_triangles
  Clock::time_point last_watch{};   // of the last look at every worker (heartbeats())
  Clock::duration longest_task{};   // of the tasks finished so far (the task bound grows with it)

  Impl(ManagerOptions o, store::ComponentStore& s, Launcher* l, Logger& lg, Progress& p, const CancelToken& c)
      : options(std::move(o)), store(s), launcher(l), log(lg), progress(p), cancel(c),
        socket(options.bind, options.max_message, beside(s.directory(), ".keys").string(), lg),
        tree(tandem::cube_cells(s.geometry().shape),
             tandem::leaf_size(options.settings.extraction, s.geometry().shape)) {
    report.leaves = tree.leaves().size();
  }

  void skip_finished_leaves();

  std::string new_token() {
    std::string t = "w" + run_prefix + "-" + std::to_string(++token_count);
    allowed.insert(t);
    return t;
  }

  void launch_one();

  bool send(const std::string& token, const Message& m) {
    ++messages_out;
    return socket.send(token, encode(m));
  }
  // The task log's line for the peer's task that just ended (before the schedule forgets it).
  void log_task(const Peer& p, std::uint64_t leaves, double worker_ms, unsigned empty = 0, double cpu_ms = -1.0,
                const detail::BatchMerges& merges = {}) {
    const double end = since(start);
    const double begun = std::chrono::duration<double>(p.task_start - start).count();
    task_log.add({.worker = p.token,
                  .kind = to_string(p.task->kind),
                  .leaf = p.task->kind == TaskKind::extract ? p.task->leaf : -1,
                  .leaves = leaves,
                  .start = begun,
                  .end = end,
                  .worker_ms = worker_ms < 0 ? 1000.0 * (end - begun) : worker_ms,
                  .bytes = p.task_bytes,
                  .rows = p.task_rows,
                  .empty = empty,
                  .cpu_ms = cpu_ms,
                  .merges = merges.merges,
                  .merge_leaves = merges.leaves,
                  .merge_bytes = merges.bytes,
                  .wire_ms = 1000.0 * merges.wire_seconds,
                  .merge_ms = 1000.0 * merges.merge_seconds,
                  .absorb_ms = 1000.0 * merges.absorb_seconds});
  }

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

  void kill_peer(const std::string& token, const std::string& why);

  // How long a task (or a worker's SETUP) may take before it is taken back: task_timeout, or 10
  // times the longest task finished so far when that is longer.
  Clock::duration task_bound() const { return std::max<Clock::duration>(options.task_timeout, 10 * longest_task); }
  void task_finished(const Peer& p) { longest_task = std::max(longest_task, Clock::now() - p.task_start); }
  void overdue_tasks();

  // Workers launched that have not said HELLO yet (nor ended).
  std::size_t workers_to_come() const { return allowed.size() - peers.size() - dead.size(); }

  std::string token_of(WorkerId id) const {
    for (const auto& [token, p] : peers)
      if (p.id == id) return token;
    return "?";
  }

  void retire(Peer& p, const std::string& why);
  void decide(Peer& p);
  void pump(Peer& p, std::uint64_t credits);
  void depart(const std::string& token);

  // Small leaves in batches (issue 55; extract_batch() in schedule.hpp). GEOTANDEM_EXTRACT_BATCH
  // caps the leaves per EXTRACT (1: one leaf per EXTRACT, the seed's algorithm).
  double extracted_seconds = 0;  // the workers' time for the leaves extracted so far
  double cpu_at_first_task = -1; // task_cpu_seconds() at the manager's first decision
  std::uint64_t extracted_leaves = 0;
  std::size_t batch_cap = detail::extract_batch_cap();
  // The manager's CPU time but its index writer's.
  double task_cpu_seconds() { return cpu_seconds() - commits.cpu_seconds(); }
  std::size_t batch_leaves() {
    const double per_leaf = extracted_leaves ? extracted_seconds / static_cast<double>(extracted_leaves) : 0.0;
    // The manager's CPU per task since its first decision, once a few tasks tell: what batches
    // save (messages, decisions, relayed chunks, ZeroMQ's thread). Not the index writer's: its cost
    // is per leaf whatever the batch, and counting it fed back (larger batches, fewer tasks, more
    // CPU per task, larger batches): clean runs settled on batches of 128 leaves, resumed ones, whose
    // writer had less to do, on 64, with 1.7x their EXTRACTs (analytic 256^3, leaves of 8, 2 workers).
    const std::uint64_t tasks = report.extract_tasks + report.merge + report.send;
    const double per_task = tasks >= 16 && cpu_at_first_task >= 0
                                ? (task_cpu_seconds() - cpu_at_first_task) / static_cast<double>(tasks)
                                : 0.0;
    return extract_batch(per_leaf, schedule.unprocessed(), peers.size(), batch_cap,
                         batch_seconds(per_task, peers.size()));
  }

  // The bar counts blocks extracted and the final pass; a re-done block does not move it twice.
  void advance() {
    if (progress_done < report.leaves + 1) progress.advance();
    ++progress_done;
  }

  // Finished leaves wait in `unrecorded` and are recorded (appended to the store's file and synced)
  // together, at most every 100 ms, after every COMMIT received so far: one fdatasync per batch,
  // not per task. A manager killed meanwhile loses their lines only: they are re-done on resume.
  std::vector<tandem::NodeId> unrecorded;
  Clock::time_point last_record{};
  void record_finished() {
    last_record = Clock::now();
    if (unrecorded.empty()) return;
    commits.then([this, leaves = std::move(unrecorded)] { finished.record(leaves); });
    unrecorded.clear();
  }
  static bool final_task(const Peer& p) { return p.task && p.task->kind == TaskKind::finished; }

  detail::BatchMerges batch_merges(const Peer& p, const Message& m);
  void task_done(Peer& p, const Message& m);
  void handle(const std::string& token, std::span<const std::byte> frame);
  void heartbeats();
  void stop_workers();
  ManagerReport run();
};

} // namespace geotandem::runtime
