// The manager's handling of its workers' messages (manager.hpp): HELLO, ASK, the results of tasks,
// the chunks of partial surfaces, and the decisions that answer them (Schedule).
#include <algorithm>

#include "manager_impl.hpp"

namespace geotandem::runtime {

// RETIRE: the worker is near its walltime. It gets no more EXTRACT and hands its surface to
// another worker (Schedule); a replacement with a fresh walltime is launched now, so that it can
// take the surface. Not counted against max_restarts: a retiring worker loses nothing.
void Manager::Impl::retire(Peer& p, const std::string& why) {
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

void Manager::Impl::decide(Peer& p) {
  schedule.expect_joins(workers_to_come());
  if (cpu_at_first_task < 0) cpu_at_first_task = task_cpu_seconds();
  schedule.set_batch(batch_leaves());
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
  if (d.kind == TaskKind::extract) {
    m.lease.attempt = ++attempts[d.leaf];
    if (d.finished > 0) m.bytes = detail::encode_runs(detail::finished_runs(tree, schedule, d.leaf));
  }
  const bool busy = d.kind != TaskKind::wait && (d.kind != TaskKind::finished || d.final);
  if (busy) {
    m.lease.task = next_task++;
    p.lease = m.lease;
    p.task = d;
    p.task_start = Clock::now();
    p.task_bytes = p.task_rows = 0;
    if (log.enabled(LogLevel::debug)) log.debug("worker " + p.token + ": " + task_text(p));
  }
  if (d.kind == TaskKind::merge) {
    const detail::SurfaceRelay::Header h = relay.begin_outbound(p.token, d.transfer);
    m.number = h.total;
    p.task_bytes = h.total;
    m.box[0] = static_cast<std::int64_t>(h.checksum);
  }
  if (d.kind == TaskKind::send) relay.begin_inbound(p.token);
  if (!send(p.token, m)) return kill_peer(p.token, "cannot be reached");
  if (d.kind == TaskKind::merge) pump(p, 0);
  if (d.kind == TaskKind::finished && !d.final) depart(p.token);
}

// The chunks of the MERGE in progress that the worker's credits allow now.
void Manager::Impl::pump(Peer& p, std::uint64_t credits) {
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
void Manager::Impl::depart(const std::string& token) {
  auto it = peers.find(token);
  if (it == peers.end()) return;
  log.info("worker " + token + " done after " + std::to_string(it->second.tasks) + " task(s)");
  schedule.leave(it->second.id);
  held_triangles -= it->second.held_triangles;
  relay.forget(token);
  dead.insert(token);
  departed.insert(token);
  peers.erase(it);
}

// The merges inside an EXTRACT's batch, from its DONE (for the task log only: a damaged figure is
// left out, the run goes on).
detail::BatchMerges Manager::Impl::batch_merges(const Peer& p, const Message& m) {
  try {
    return detail::decode_merges(m.bytes);
  } catch (const ProtocolError& e) {
    log.warning("worker " + p.token + ": " + e.what() + "; the task log leaves its batch's merges out");
    return {};
  }
}

void Manager::Impl::task_done(Peer& p, const Message& m) {
  // The task's wall time as the worker measured it (box[5], microseconds); number is its CPU time.
  const double s = static_cast<double>(m.box[5]) / 1e6;
  {
    std::uint64_t leaves = 1;
    if (p.task->kind == TaskKind::extract) leaves = schedule.leaves_under(p.task->leaf) - p.task->finished;
    if (p.task->kind == TaskKind::merge) leaves = schedule.transfer_leaves(p.task->transfer);
    if (p.task->kind == TaskKind::finished) leaves = schedule.leaves_held(p.id);
    // box[5]: microseconds (0 from a worker that does not send them: the milliseconds then).
    const bool piece_task = p.task->kind == TaskKind::extract || p.task->kind == TaskKind::merge;
    const detail::BatchMerges merges = p.task->kind == TaskKind::extract ? batch_merges(p, m) : detail::BatchMerges{};
    log_task(p, leaves, static_cast<double>(m.box[5]) / 1000.0, piece_task ? static_cast<unsigned>(m.box[1] & 3) : 0u,
             static_cast<double>(m.number) / 1000.0, merges);
  }
  report.worker_peak_rss_kb = std::max(report.worker_peak_rss_kb, m.box[0]);
  switch (p.task->kind) {
  case TaskKind::extract: {
    const std::size_t n = schedule.leaves_under(p.task->leaf) - p.task->finished; // extracted
    report.extract += n, report.seconds_extract += s;
    ++report.extract_tasks;
    extracted_leaves += n;
    extracted_seconds += s;
    for (std::size_t i = 0; i < n; ++i)
      advance();
    break;
  }
  case TaskKind::merge: ++report.merge, report.seconds_merge += s; break;
  case TaskKind::finished: {
    ++report.finish, report.seconds_finish += s, advance();
    // The two totals of box[2] and box[3], then every counter from the text when it is there;
    // added to those of the surfaces dropped empty on the way.
    tandem::SimplifyCounters whole;
    whole.input_triangles = static_cast<std::uint64_t>(m.box[2]);
    whole.collapses = static_cast<std::uint64_t>(m.box[3]);
    try {
      if (!m.text.empty()) whole = counters_from_json(m.text);
    } catch (const ProtocolError& e) { // statistics only: the run goes on without them
      log.warning("worker " + p.token + ": " + e.what() + "; the run's collapse counters are left out");
    }
    report.counters += whole;
    break;
  }
  default: break;
  }
  // An EXTRACT or a MERGE that left the worker's surface empty: it dropped it (worker.cpp), with
  // the counters of that surface in the text.
  const bool emptied = (m.box[1] & 1) == 1 && (p.task->kind == TaskKind::extract || p.task->kind == TaskKind::merge);
  if (emptied && !m.text.empty()) {
    try {
      report.counters += counters_from_json(m.text);
    } catch (const ProtocolError& e) {
      log.warning("worker " + p.token + ": " + e.what() + "; a dropped surface's counters are left out");
    }
  }
  task_finished(p);
  ++p.tasks;
  held_triangles -= p.held_triangles;
  p.held_triangles = static_cast<std::uint64_t>(std::max<std::int64_t>(m.box[4], 0));
  held_triangles += p.held_triangles;
  report.peak_held_triangles = std::max(report.peak_held_triangles, held_triangles);
  if (log.enabled(LogLevel::debug)) log.debug("triangles held by the workers: " + std::to_string(held_triangles));
  // An empty surface: its leaves' components are all committed (the COMMIT came first). The leaves
  // recorded before are not looked at again: the cost stays with the leaves new to its surface.
  if ((m.box[1] & 1) == 1) {
    std::vector<tandem::NodeId> leaves = schedule.take_unrecorded(p.id);
    if (log.enabled(LogLevel::debug))
      log.debug("worker " + p.token + ": surface empty after " + task_text(p) + "; " + std::to_string(leaves.size()) +
                " more leaves finished");
    unrecorded.insert(unrecorded.end(), leaves.begin(), leaves.end());
    if (final_task(p)) record_finished(); // the run's last leaves: at once
  }
  const bool final = p.task->kind == TaskKind::finished;
  p.task.reset();
  schedule.done(p.id, emptied);
  if (final) depart(p.token);
}

void Manager::Impl::handle(const std::string& token, std::span<const std::byte> frame) {
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
  ++messages_in;
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
    Peer p{.id = next_worker++, .token = token, .pid = m.number, .heard = Clock::now(), .joined = Clock::now()};
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
    p.asked = true;
    if (p.task) { // it lost its task (a message dropped on the way): its work is re-done elsewhere
      drop("ASK from worker " + token + " while it has a task (" + task_text(p) + ")");
      return kill_peer(token, "asked again without finishing its task");
    }
    return decide(p);
  case MessageKind::retire:
    p.asked = true;
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
    if (p.task->kind == TaskKind::merge && m.number == 5) { // DataError
      // The record it was to merge was refused (issue 52: it may come from a stranger or a broken
      // worker): the run goes on without that worker, whose blocks and the record's are re-done.
      log.error("failed during " + task_text(p) + ": " + m.text);
      return kill_peer(token, "refused the partial surface it was to merge");
    }
    detail::throw_worker_failure(static_cast<int>(m.number), "failed during " + task_text(p) + ": " + m.text, token,
                                 "fix the cause and rerun the same command: committed components are kept");
  default: break;
  }
  if (!p.task || !(m.lease == p.lease))
    return drop(std::string(to_string(m.kind)) + " from worker " + token + " with a stale lease (task " +
                std::to_string(m.lease.task) + ", attempt " + std::to_string(m.lease.attempt) + ")");
  switch (m.kind) {
  case MessageKind::commit:
    p.task_rows += m.entries.size();
    rows_in += m.entries.size();
    commits.commit(std::move(m.entries));
    return;
  case MessageKind::surface_chunk: {
    if (p.task->kind != TaskKind::send) return drop("a surface chunk from worker " + token + " outside a SEND");
    const auto size_hint = static_cast<std::uint64_t>(std::max<std::int64_t>(0, m.box[0]));
    if (const std::optional<std::string> why = relay.chunk_in(token, m.number, m.bytes, size_hint)) {
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
    p.task_bytes = bytes;
    log_task(p, schedule.transfer_leaves(t), -1.0);
    report.largest_surface = std::max<std::uint64_t>(report.largest_surface, bytes);
    ++report.send;
    task_finished(p);
    ++p.tasks;
    p.task.reset();
    if (schedule.arrived(p.id, t))
      if (const std::optional<std::string> warning = relay.keep(token, t)) log.warning(*warning);
    relay.forget(token);
    return;
  }
  case MessageKind::done:
    if (p.task->kind == TaskKind::send) return drop("DONE from worker " + token + " for a SEND");
    return task_done(p, m);
  default: return drop(std::string("unexpected ") + to_string(m.kind) + " from worker " + token);
  }
}

} // namespace geotandem::runtime
