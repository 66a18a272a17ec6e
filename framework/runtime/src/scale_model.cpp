// The scale model: a recorded run replayed through the real Schedule (scale_model.hpp).
#include "geotandem/runtime/scale_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <queue>
#include <utility>

#include "geotandem/core/error.hpp"
#include "geotandem/runtime/aggregate.hpp"
#include "geotandem/runtime/schedule.hpp"

namespace geotandem::runtime {

namespace {

using tandem::NodeId;

// Least squares y = a + b x; b = 0 (a = mean) with fewer than two distinct x.
std::pair<double, double> fit_line(const std::vector<std::pair<double, double>>& xy) {
  if (xy.empty()) return {0.0, 0.0};
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& [x, y] : xy) {
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double n = static_cast<double>(xy.size());
  const double den = n * sxx - sx * sx;
  if (xy.size() < 2 || std::abs(den) < 1e-12 * std::max(1.0, n * sxx)) return {sy / n, 0.0};
  double b = (n * sxy - sx * sy) / den;
  double a = (sy - b * sx) / n;
  if (b < 0) return {sy / n, 0.0}; // noise: no cost per byte below zero
  if (a < 0) {                     // through the origin
    b = sxy / sxx;
    a = 0;
  }
  return {a, b};
}

std::int64_t cells_of(const volume::Box& b) {
  return b.size(0) * b.size(1) * b.size(2);
}

constexpr double kWait = 0.020;                         // the manager's WAIT (manager_support.cpp)
constexpr double kChunk = static_cast<double>(1 << 20); // bytes per surface chunk (protocol.hpp)

double mean(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v)
    sum += x;
  return v.empty() ? 0.0 : std::max(0.0, sum / static_cast<double>(v.size()));
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return std::max(0.0, v[v.size() / 2]);
}

} // namespace

ScaleModelCalibration calibrate(const TaskLogRun& run) {
  ScaleModelCalibration c;
  c.cube = run.cube;
  c.leaf_size = run.leaf_size;
  const tandem::BlockTree tree(run.cube, run.leaf_size);
  c.extract.assign(tree.size(), std::numeric_limits<double>::quiet_NaN());
  c.solid.assign(tree.size(), 1);
  c.drops = run.empties;
  c.batch = run.batch;
  std::vector<std::pair<double, double>> merges, sends, sizes;
  // The merges inside batches (the task log's columns), per EXTRACT: a record's mean bytes against
  // the mean time to merge it and to serialise it, and its mean leaves against its bytes. They price
  // a SEND and a MERGE when the log has none (a 1-worker run) or too few to fit.
  std::vector<std::pair<double, double>> batch_merges, batch_wires, batch_sizes;
  // An EXTRACT's surface merged into the one its worker held (absorb), by the leaves it extracted:
  // a merge into a large surface, as a MERGE is (the merges inside a batch are into small ones).
  std::vector<std::pair<double, double>> absorbs;
  std::map<std::string, double> first_task;
  double extract_sum = 0;
  std::size_t extracts = 0;
  std::map<std::string, std::vector<double>> over;
  std::map<std::string, double> last_end;
  std::vector<double> gaps;
  double cpu_sum = 0, cpu_wall = 0; // the workers' CPU and wall seconds in EXTRACT and MERGE
  for (const TaskRecord& t : run.tasks) {
    if (t.kind != "SEND") over[t.kind].push_back(t.end - t.start - t.worker_ms / 1000.0);
    if (auto e = last_end.find(t.worker); e != last_end.end()) gaps.push_back(t.start - e->second);
    last_end[t.worker] = t.end;
    auto [it, fresh] = first_task.try_emplace(t.worker, t.start);
    if (!fresh) it->second = std::min(it->second, t.start);
    const double s = t.worker_ms / 1000.0;
    if ((t.kind == "EXTRACT" || t.kind == "MERGE") && t.cpu_ms >= 0) {
      cpu_sum += t.cpu_ms / 1000.0;
      cpu_wall += s;
    }
    if (t.kind == "EXTRACT" && t.leaf >= 0 && static_cast<std::size_t>(t.leaf) < tree.size()) {
      // A batch: its node's leaves share its time evenly (they include the merges inside it). A
      // batch may span leaves finished before (Schedule::set_batch; the log counts the leaves it
      // extracted): when the leaves not timed yet are as many, they are the ones it extracted.
      const NodeId end = subtree_end(tree, static_cast<NodeId>(t.leaf));
      std::size_t k = 0, untimed = 0;
      for (NodeId n = static_cast<NodeId>(t.leaf); n < end; ++n)
        if (tree.node(n).is_leaf()) {
          ++k;
          untimed += std::isnan(c.extract[static_cast<std::size_t>(n)]) ? 1 : 0;
        }
      const bool only_fresh = untimed > 0 && untimed < k && untimed == t.leaves;
      if (only_fresh) k = untimed;
      for (NodeId n = static_cast<NodeId>(t.leaf); n < end; ++n) {
        if (!tree.node(n).is_leaf() || (only_fresh && !std::isnan(c.extract[static_cast<std::size_t>(n)]))) continue;
        c.extract[static_cast<std::size_t>(n)] = s / static_cast<double>(k);
        c.solid[static_cast<std::size_t>(n)] = run.empties && (t.empty & 2) != 0 ? 0 : 1;
      }
      extract_sum += s;
      extracts += k;
      if (t.absorb_ms > 0 && t.leaves > 0) absorbs.emplace_back(static_cast<double>(t.leaves), t.absorb_ms / 1000.0);
      if (t.merges > 0 && t.merge_bytes > 0) {
        const double n = static_cast<double>(t.merges), bytes = static_cast<double>(t.merge_bytes) / n;
        batch_merges.emplace_back(bytes, t.merge_ms / 1000.0 / n);
        batch_wires.emplace_back(bytes, t.wire_ms / 1000.0 / n);
        if (t.merge_leaves > 0)
          batch_sizes.emplace_back(std::log(static_cast<double>(t.merge_leaves) / n), std::log(bytes));
      }
    } else if (t.kind == "MERGE") {
      merges.emplace_back(static_cast<double>(t.bytes), s);
    } else if (t.kind == "SEND") {
      sends.emplace_back(static_cast<double>(t.bytes), s);
      if (t.leaves > 0 && t.bytes > 0)
        sizes.emplace_back(std::log(static_cast<double>(t.leaves)), std::log(static_cast<double>(t.bytes)));
    } else if (t.kind == "FINISHED") {
      c.finish_seconds = s;
      c.finish_leaves = t.leaves;
    }
  }
  if (extracts == 0) throw InvalidArgument("the task log's run has no EXTRACT: nothing to model");
  c.extract_mean = extract_sum / static_cast<double>(extracts);
  // The mean, not the median: the replay must add up to what the log records, and the overheads are
  // skewed (a task whose result waits behind a SEND's chunks at the manager).
  c.overhead_extract = mean(over["EXTRACT"]);
  // A log without MERGE (1 worker): a MERGE's messages there and back cost what an EXTRACT's do.
  c.overhead_merge = over["MERGE"].empty() ? c.overhead_extract : mean(over["MERGE"]);
  c.overhead_finish = mean(over["FINISHED"]);
  c.gap = median(gaps);
  if (sends.size() < 2 && !batch_wires.empty()) sends.insert(sends.end(), batch_wires.begin(), batch_wires.end());
  if (sizes.size() < 2 && !batch_sizes.empty()) sizes.insert(sizes.end(), batch_sizes.begin(), batch_sizes.end());
  c.batch_merges = batch_merges.size();
  std::tie(c.send_fixed, c.send_per_byte) = fit_line(sends);
  // A partial surface is the open front of its region: it grows like the region's faces, not its
  // volume. The exponent is fitted where the SENDs cover several sizes, kept within [1/2, 1], and
  // taken as 2/3 (faces of a cube of leaves) when they do not.
  if (!sizes.empty()) {
    auto [a, b] = fit_line(sizes);
    c.bytes_p = b > 0 ? std::clamp(b, 0.5, 1.0) : 2.0 / 3.0;
    double log_k = 0;
    for (const auto& [log_leaves, log_bytes] : sizes)
      log_k += (log_bytes - c.bytes_p * log_leaves) / static_cast<double>(sizes.size());
    c.bytes_k = std::exp(log_k);
    (void)a;
  }
  // Without MERGEs to fit, the absorbs priced in the same bytes (the size law above; without one, a
  // log of single-leaf EXTRACTs and no SEND, at their mean: a fixed price), else the merges inside
  // batches.
  if (merges.size() < 2 && !absorbs.empty()) {
    for (const auto& [leaves, seconds] : absorbs)
      merges.emplace_back(c.bytes_k > 0 ? c.bytes_k * std::pow(leaves, c.bytes_p) : 0.0, seconds);
  } else if (merges.size() < 2) {
    merges.insert(merges.end(), batch_merges.begin(), batch_merges.end());
  }
  std::tie(c.merge_fixed, c.merge_per_byte) = fit_line(merges);
  const double messages = static_cast<double>(run.messages_in + run.messages_out);
  // The manager's CPU but its index writer's (modelled apart, per leaf) spread over its messages.
  const double writer_cpu = std::clamp(run.commit_cpu_seconds, 0.0, run.manager_cpu_seconds);
  c.manager_per_message = messages > 0 ? (run.manager_cpu_seconds - writer_cpu) / messages : 0;
  // The index writer's whole busy time (rows, and the finished leaves it records) spread over the
  // leaves: per row it would make a run of few rows and many records look absurd.
  c.index_per_row = run.commit_seconds / static_cast<double>(extracts);
  c.rows_per_leaf = 1;
  for (const auto& [w, t] : first_task)
    c.startup += t / static_cast<double>(first_task.size());
  c.recorded_workers = run.workers ? run.workers : first_task.size();
  // The processors: the workers' CPU over their wall time in their tasks is the share of a core a
  // worker got; with the host's cores, the workers and the manager's share of a core, what is left
  // unexplained is the machine's other load (background), assumed constant and shared fairly.
  c.cores = run.cores;
  c.manager_share = run.wall_seconds > 0 ? std::min(1.0, run.manager_cpu_seconds / run.wall_seconds) : 0.0;
  if (cpu_wall > 0 && cpu_sum > 0) {
    c.cpu_share = std::clamp(cpu_sum / cpu_wall, 0.02, 1.0);
    if (c.cores > 0 && c.cpu_share < 0.97)
      c.background = std::max(0.0, static_cast<double>(c.cores) / c.cpu_share -
                                       static_cast<double>(c.recorded_workers) - c.manager_share);
  }
  c.recorded_wall = run.wall_seconds;
  c.recorded_manager_cpu = run.manager_cpu_seconds;
  return c;
}

double cpu_share(const ScaleModelCalibration& c, std::size_t cores, std::size_t workers) {
  if (cores == 0) return 1.0;
  const double runnable = static_cast<double>(workers) + c.manager_share + c.background;
  return std::min(1.0, static_cast<double>(cores) / runnable);
}

ScalePrediction predict(const ScaleModelCalibration& c, const tandem::BlockTree& tree, std::size_t workers,
                        std::size_t cores) {
  // Each leaf's time: the recorded leaf at the same relative position, scaled by cells.
  const tandem::BlockTree recorded(c.cube, c.leaf_size);
  std::vector<double> extract(tree.size(), 0.0);
  std::vector<char> solid(tree.size(), 1);
  const volume::Box& to = tree.cube();
  for (NodeId leaf : tree.leaves()) {
    const volume::Box& b = tree.node(leaf).cells;
    volume::Index3 at{};
    for (int a = 0; a < 3; ++a) {
      const double centre =
          0.5 * static_cast<double>(b.lo[a] + b.hi[a] - 2 * to.lo[a]) / static_cast<double>(to.size(a));
      at[a] = c.cube.lo[a] +
              std::min<std::int64_t>(c.cube.size(a) - 1,
                                     static_cast<std::int64_t>(centre * static_cast<double>(c.cube.size(a))));
    }
    const NodeId r = recorded.leaf_of(at);
    if (r >= 0 && static_cast<std::size_t>(r) < c.solid.size())
      solid[static_cast<std::size_t>(leaf)] = c.solid[static_cast<std::size_t>(r)];
    double s = r >= 0 ? c.extract[static_cast<std::size_t>(r)] : c.extract_mean;
    if (std::isnan(s)) s = c.extract_mean;
    if (r >= 0) s *= static_cast<double>(cells_of(b)) / static_cast<double>(cells_of(recorded.node(r).cells));
    extract[static_cast<std::size_t>(leaf)] = s;
  }
  const auto bytes_of = [&](std::size_t leaves) {
    return leaves == 0 ? 0.0 : c.bytes_k * std::pow(static_cast<double>(leaves), c.bytes_p);
  };
  // The final pass finishes what is still open at the end, whatever the workers: its recorded time,
  // scaled with the surface of the cube when the cube is not the recorded one (by the leaves the
  // final worker holds it was 2000x too slow: it holds every leaf a batch spanned, and on a 1-worker
  // log the size law, fitted on the merges inside batches, is linear).
  const double finish = bytes_of(recorded.leaves().size()) > 0
                            ? c.finish_seconds * bytes_of(tree.leaves().size()) / bytes_of(recorded.leaves().size())
                            : c.finish_seconds;

  // The processors (see scale_model.hpp): a worker's share of a core in the recorded run and in this
  // one; the recorded times are stretched or shrunk by their ratio.
  const double slow = cores > 0 ? c.cpu_share / cpu_share(c, cores, workers) : 1.0;
  Schedule schedule(tree);
  ScalePrediction out;
  out.cpu_share = cores > 0 ? cpu_share(c, cores, workers) : 1.0;
  out.workers = workers;
  enum class Event { ask, done };
  struct Item {
    double t;
    std::uint64_t seq;
    WorkerId w;
    Event e;
    bool operator>(const Item& o) const { return t != o.t ? t > o.t : seq > o.seq; }
  };
  std::priority_queue<Item, std::vector<Item>, std::greater<>> events;
  std::uint64_t seq = 0;
  std::map<WorkerId, Decision> task;
  std::map<WorkerId, double> task_bytes;
  // Empty surfaces (the recorded run dropped them): a worker's surface is taken as empty when none
  // of the leaves it holds left anything open by itself; solid leaves held by worker and by transfer.
  std::map<WorkerId, std::size_t> solid_held;
  std::map<TransferId, std::size_t> solid_sent;
  double leaf_seconds = 0; // of the simulated leaves extracted so far (the manager's batch policy)
  std::uint64_t leaves_done = 0;
  double manager_free = 0, manager_busy = 0, manager_waited = 0, index_free = 0, index_busy = 0;
  std::uint64_t manager_messages = 0;
  double last_extract_end = 0;
  // The manager handles `n` messages that arrive at `t`, one after the other; returns when done.
  const auto manager = [&](double t, double n) {
    const double begin = std::max(t, manager_free);
    manager_waited += begin - t;
    ++manager_messages;
    manager_free = begin + n * c.manager_per_message;
    manager_busy += n * c.manager_per_message;
    return manager_free;
  };
  for (WorkerId w = 1; w <= workers; ++w) {
    schedule.join(w);
    events.push({c.startup * slow, seq++, w, Event::ask}); // starting is CPU work too (exec, libraries, SETUP)
  }
  while (!events.empty()) {
    const Item it = events.top();
    events.pop();
    if (it.e == Event::ask) {
      const double t = manager(it.t, 2); // ASK and the answer
      const std::uint64_t tasks = out.extract + out.send + out.merge;
      const double per_task = tasks >= 16 ? manager_busy / static_cast<double>(tasks) : 0.0;
      schedule.set_batch(extract_batch(leaves_done ? leaf_seconds / static_cast<double>(leaves_done) : 0.0,
                                       schedule.unprocessed(), schedule.live_workers(), c.batch,
                                       batch_seconds(per_task, schedule.live_workers())));
      const Decision d = schedule.next(it.w);
      double busy = 0;
      switch (d.kind) {
      case TaskKind::wait:
        ++out.wait;
        events.push({t + kWait, seq++, it.w, Event::ask});
        continue;
      case TaskKind::extract: {
        ++out.extract;
        double s = 0;
        for (NodeId n = d.leaf, end = subtree_end(tree, d.leaf); n < end; ++n)
          if (tree.node(n).is_leaf() && !schedule.finished(n)) { // a batch's finished leaves are skipped
            s += extract[static_cast<std::size_t>(n)];
            solid_held[it.w] += solid[static_cast<std::size_t>(n)] ? 1 : 0;
          }
        leaf_seconds += s;
        leaves_done += schedule.leaves_under(d.leaf) - d.finished;
        busy = s * slow + c.overhead_extract;
        last_extract_end = std::max(last_extract_end, t + busy);
        task_bytes[it.w] = 0;
        break;
      }
      case TaskKind::send: {
        ++out.send;
        solid_sent[d.transfer] = std::exchange(solid_held[it.w], 0);
        const double bytes = bytes_of(schedule.transfer_leaves(d.transfer));
        busy = (c.send_fixed + c.send_per_byte * bytes) * slow;
        task_bytes[it.w] = bytes;
        break;
      }
      case TaskKind::merge: {
        ++out.merge;
        solid_held[it.w] += solid_sent[d.transfer];
        solid_sent.erase(d.transfer);
        const double bytes = bytes_of(schedule.transfer_leaves(d.transfer));
        busy = (c.merge_fixed + c.merge_per_byte * bytes) * slow + c.overhead_merge;
        task_bytes[it.w] = bytes;
        break;
      }
      case TaskKind::finished:
        if (!d.final) {
          schedule.leave(it.w);
          continue;
        }
        busy = finish * slow + c.overhead_finish;
        task_bytes[it.w] = 0;
        break;
      }
      out.work += busy;
      task[it.w] = d;
      events.push({t + busy, seq++, it.w, Event::done});
      continue;
    }
    const Decision d = task.at(it.w);
    task.erase(it.w);
    const double chunks = std::ceil(task_bytes[it.w] / kChunk);
    const double rows = d.kind == TaskKind::extract ? c.rows_per_leaf : 0;
    const double t = manager(it.t, 1 + (rows > 0 ? 1 : 0) + 2 * chunks); // DONE, COMMIT, chunks and credits
    if (rows > 0) {
      const double begin = std::max(t, index_free);
      index_free = begin + rows * c.index_per_row;
      index_busy += rows * c.index_per_row;
    }
    if (d.kind == TaskKind::send) {
      schedule.arrived(it.w, d.transfer);
    } else {
      const bool emptied = c.drops && d.kind != TaskKind::finished && solid_held[it.w] == 0;
      schedule.done(it.w, emptied);
      if (d.kind == TaskKind::finished) {
        out.wall = std::max(t, index_free);
        break;
      }
    }
    events.push({t + c.gap, seq++, it.w, Event::ask});
  }
  if (out.wall <= 0) throw Error("the scale model's replay did not finish the run");
  out.manager_busy = manager_busy / out.wall;
  out.index_busy = index_busy / out.wall;
  out.tail = out.wall - last_extract_end;
  out.manager_wait = manager_messages ? manager_waited / static_cast<double>(manager_messages) : 0;
  const double tail_share = out.tail / out.wall;
  const double top = std::max({out.manager_busy, out.index_busy, tail_share});
  if (top < 0.2)
    out.saturates = "nothing (the workers)";
  else if (top == out.manager_busy)
    out.saturates = "manager";
  else if (top == out.index_busy)
    out.saturates = "index writer";
  else
    out.saturates = "merges near the root";
  return out;
}

} // namespace geotandem::runtime
