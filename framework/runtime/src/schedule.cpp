// The manager's decisions, algorithm 6 of the seed (schedule.hpp).
#include "geotandem/runtime/schedule.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "geotandem/core/error.hpp"
#include "leaf_counts.hpp"

namespace geotandem::runtime {

using tandem::kNoNode;
using tandem::NodeId;

const char* to_string(TaskKind kind) {
  switch (kind) {
  case TaskKind::extract: return "EXTRACT";
  case TaskKind::send: return "SEND";
  case TaskKind::merge: return "MERGE";
  case TaskKind::wait: return "WAIT";
  case TaskKind::finished: return "FINISHED";
  }
  return "?";
}

double batch_seconds(double manager_cpu_per_task, std::size_t workers) {
  // `workers` tasks of T seconds cost the manager workers * c every T: at most kManagerShare of it.
  const double needed = static_cast<double>(std::max<std::size_t>(workers, 1)) * manager_cpu_per_task / kManagerShare;
  return std::clamp(needed, kBatchSeconds, 1.0);
}

std::size_t extract_batch(double leaf_seconds, std::size_t unprocessed, std::size_t workers, std::size_t cap,
                          double target) {
  if (cap <= 1 || !(leaf_seconds > 0)) return 1;
  const double by_time = target / std::max(leaf_seconds, 1e-7);
  const std::size_t by_balance = unprocessed / (4 * std::max<std::size_t>(workers, 1));
  const double most = std::min({by_time, static_cast<double>(by_balance), static_cast<double>(cap)});
  std::size_t n = 1;
  while (static_cast<double>(2 * n) <= most)
    n *= 2;
  return n;
}

Schedule::Schedule(const tandem::BlockTree& tree)
    : tree_(tree), unprocessed_(tree.size(), 0), unprocessed_count_(tree.leaves().size()),
      open_(std::make_unique<detail::LeafCounts>(tree)), taken_(std::make_unique<detail::LeafCounts>(tree)),
      owner_(tree.size(), 0), leaves_under_(tree.size(), 0), finished_(tree.size(), 0) {
  for (NodeId leaf : tree.leaves())
    unprocessed_[static_cast<std::size_t>(leaf)] = 1;
  open_->count_every_leaf();
  // Ids are in depth-first order, a parent before its children: children are counted first.
  for (std::size_t i = tree.size(); i-- > 0;) {
    const tandem::BlockNode& n = tree.node(static_cast<NodeId>(i));
    leaves_under_[i] = n.is_leaf() ? 1
                                   : leaves_under_[static_cast<std::size_t>(n.children[0])] +
                                         leaves_under_[static_cast<std::size_t>(n.children[1])];
  }
}

Schedule::~Schedule() = default;

void Schedule::skip(NodeId leaf) {
  if (started_) throw std::logic_error("schedule: skip() after the first decision");
  if (leaf < 0 || static_cast<std::size_t>(leaf) >= tree_.size() || !tree_.node(leaf).is_leaf())
    throw InvalidArgument("schedule: node " + std::to_string(leaf) + " is not a leaf of the block tree");
  if (!unprocessed_[static_cast<std::size_t>(leaf)]) return;
  ++skipped_;
  ++loose_;
  finished_[static_cast<std::size_t>(leaf)] = 1;
  unprocessed_[static_cast<std::size_t>(leaf)] = 0;
  --unprocessed_count_;
  open_->change(leaf, -1);
}

Schedule::Worker& Schedule::worker(WorkerId id) {
  auto it = workers_.find(id);
  if (it == workers_.end()) throw std::logic_error("schedule: unknown worker " + std::to_string(id));
  return it->second;
}

void Schedule::join(WorkerId id) {
  if (!workers_.try_emplace(id, tree_).second)
    throw std::logic_error("schedule: worker " + std::to_string(id) + " joined twice");
}

bool Schedule::busy(WorkerId id) const {
  auto it = workers_.find(id);
  return it != workers_.end() && it->second.task.has_value();
}

Aggregate Schedule::claimed(const Worker& w) const {
  Aggregate all = w.held;
  for (const auto& [order, t] : w.incoming)
    all.add(transfers_.at(t).leaves);
  return all;
}

Decision Schedule::assign(Worker& w, Decision d) {
  switch (d.kind) {
  case TaskKind::extract: ++counts_.extract; break;
  case TaskKind::send: ++counts_.send; break;
  case TaskKind::merge: ++counts_.merge; break;
  case TaskKind::wait: ++counts_.wait; return d; // nothing in progress
  case TaskKind::finished:
    ++counts_.finished;
    if (!d.final) return d;
    break;
  }
  w.task = d;
  return d;
}

Decision Schedule::send_to(WorkerId id, Worker& w, WorkerId target) {
  const TransferId t = next_transfer_++;
  move_claim(w.held, id, target);
  transfers_.emplace(t, Transfer{.from = id, .to = target, .leaves = w.held, .fresh = std::move(w.fresh)});
  w.fresh.clear();
  address(t, target);
  w.held.clear();
  return assign(w, {.kind = TaskKind::send, .target = target, .transfer = t});
}

// Who takes over `leaves` from the retiring worker `id`: a live worker that is not retiring, the
// restricted-adjacent one claiming most leaves first, else the one claiming most (adjacent or
// not, as any_holder), else any.
std::optional<WorkerId> Schedule::successor(const Aggregate& leaves, WorkerId id) {
  std::optional<WorkerId> best;
  std::size_t best_rank = 0;
  for (const auto& [other, w] : workers_) {
    if (other == id || w.retiring) continue;
    const Aggregate theirs = claimed(w); // O(maximal nodes): only for a retiring worker
    const bool adjacent = !theirs.empty() && !leaves.empty() && leaves.adjacent(theirs);
    const std::size_t rank = 1 + theirs.size() + (adjacent ? tree_.size() : 0);
    if (rank > best_rank) {
      best = other;
      best_rank = rank;
    }
  }
  return best;
}

bool Schedule::retiring(WorkerId id) const {
  auto it = workers_.find(id);
  return it != workers_.end() && it->second.retiring;
}

void Schedule::retire(WorkerId id) {
  worker(id).retiring = true;
  redirect_incoming(id);
}

// The surfaces on their way to a retiring worker (not yet being merged) go to its successor; the
// manager keeps their bytes by transfer, so only the target changes.
void Schedule::address(TransferId t, WorkerId to) {
  Transfer& tr = transfers_.at(t);
  Worker& w = worker(to);
  tr.to = to;
  tr.order = next_order_++;
  w.incoming.emplace(tr.order, t);
  if (tr.arrived && !tr.merging) w.ready.insert(tr.order);
}

TransferId Schedule::take_ready(Worker& w) {
  if (w.ready.empty()) return 0;
  const TransferId t = w.incoming.at(*w.ready.begin());
  w.ready.erase(w.ready.begin());
  Transfer& tr = transfers_.at(t);
  tr.merging = true;
  w.held.add(tr.leaves);
  w.fresh.insert(w.fresh.end(), tr.fresh.begin(), tr.fresh.end());
  tr.fresh.clear();
  return t;
}

void Schedule::redirect_incoming(WorkerId id) {
  Worker& w = worker(id);
  for (auto it = w.incoming.begin(); it != w.incoming.end();) {
    const TransferId t = it->second;
    Transfer& tr = transfers_.at(t);
    const std::optional<WorkerId> v = tr.merging ? std::nullopt : successor(tr.leaves, id);
    if (!v) {
      ++it;
      continue;
    }
    move_claim(tr.leaves, id, *v);
    w.ready.erase(tr.order);
    it = w.incoming.erase(it);
    address(t, *v);
  }
}

Decision Schedule::next_retiring(WorkerId id, Worker& w) {
  redirect_incoming(id); // a successor may have joined since
  // Nobody else to take it: merged here, then handed back.
  if (const TransferId t = take_ready(w)) return assign(w, {.kind = TaskKind::merge, .transfer = t});
  if (!w.incoming.empty()) return assign(w, {.kind = TaskKind::wait});
  if (!w.held.empty()) {
    if (const std::optional<WorkerId> v = successor(w.held, id)) {
      ++counts_.handback;
      return send_to(id, w, *v);
    }
    // Nobody to take it, and it holds the whole surface: it finishes the run itself rather than
    // have everything re-done.
    if (transfers_.empty() && w.held.size() == tree_.leaves().size() - loose_)
      return assign(w, {.kind = TaskKind::finished, .final = true});
    if (awaited_ > 0) return assign(w, {.kind = TaskKind::wait}); // a successor is on its way
  }
  // Nothing held, or nobody to take it: it stops (the transport makes it leave; what it still
  // holds is re-done from the volume).
  return assign(w, {.kind = TaskKind::finished});
}

Decision Schedule::next(WorkerId id) {
  started_ = true;
  Worker& w = worker(id);
  if (w.task) throw std::logic_error("schedule: worker " + std::to_string(id) + " asked while busy");
  if (complete_) return assign(w, {.kind = TaskKind::finished});
  if (w.retiring) return next_retiring(id, w);

  // 1. has_waiting_surface
  if (const TransferId t = take_ready(w)) return assign(w, {.kind = TaskKind::merge, .transfer = t});
  // A surface still on its way is not waiting yet: its target does not send its own away (it is
  // the target), but it extracts meanwhile rather than idle; it waits only with nothing to extract.
  const bool expecting = !w.incoming.empty();

  // 2. has_neighbor_worker
  if (!w.held.empty() && !expecting)
    if (const std::optional<WorkerId> v = neighbor(id)) return send_to(id, w, *v);

  // 3. has_unprocessed_block
  const NodeId leaf = unprocessed_leaf(w);
  if (expecting && leaf == kNoNode) return assign(w, {.kind = TaskKind::wait});
  if (leaf != kNoNode) {
    const NodeId node = batch_of(leaf);
    const std::uint32_t finished = take_leaves(id, w, node);
    return assign(w, {.kind = TaskKind::extract, .leaf = node, .finished = finished});
  }

  // Finished leaves that no batch took in (skipped by a resume, dropped with an empty surface) can
  // leave gaps between the aggregates that the restricted adjacency never bridges (any_holder).
  if (loose_ > 0 && !w.held.empty() && unprocessed() == 0)
    if (const std::optional<WorkerId> v = any_holder(id)) return send_to(id, w, *v);

  // Every leaf finished, none held: a resumed run with nothing left to do, or a run whose surfaces
  // all ended empty.
  if (loose_ == tree_.leaves().size()) {
    complete_ = true;
    return assign(w, {.kind = TaskKind::finished});
  }
  // 4. The whole surface in one worker, nothing on its way: it finishes the run.
  if (transfers_.empty() && !w.held.empty() && w.held.size() == tree_.leaves().size() - loose_)
    return assign(w, {.kind = TaskKind::finished, .final = true});
  return assign(w, {.kind = TaskKind::wait});
}

// The subtree grows while no live worker claims a leaf of it: its leaves are unprocessed or
// finished (skipped, dropped). Stopping at finished leaves instead cut a resumed run's tree into
// smaller batches and, between them, more merges (1056 EXTRACTs and 559 merges against a clean
// run's 592 and 350 on the analytic 256^3 cube, leaves of 8, 488 leaves finished before the kill).
NodeId Schedule::batch_of(NodeId leaf) const {
  NodeId node = leaf;
  while (batch_ > 1 && node != tree_.root()) {
    const NodeId up = tree_.node(node).parent;
    if (leaves_under_[static_cast<std::size_t>(up)] > batch_ || taken_->total(up) != 0) break;
    node = up;
  }
  return node;
}

std::uint32_t Schedule::take_leaves(WorkerId id, Worker& w, NodeId node) {
  std::uint32_t finished = 0;
  const NodeId end = subtree_end(tree_, node);
  for (NodeId leaf = node; leaf < end; ++leaf) {
    if (!tree_.node(leaf).is_leaf()) continue;
    if (finished_[static_cast<std::size_t>(leaf)]) {
      // Claimed by nobody (batch_of): held from now on, but neither extracted nor recorded again.
      --loose_;
      ++finished;
    } else {
      unprocessed_[static_cast<std::size_t>(leaf)] = 0;
      --unprocessed_count_;
      open_->change(leaf, -1);
      w.fresh.push_back(leaf);
    }
    taken_->change(leaf, +1);
    w.held.add(leaf);
    claim_node(id, leaf);
    ++w.claimed;
  }
  return finished;
}

void Schedule::done(WorkerId id, bool emptied) {
  Worker& w = worker(id);
  if (!w.task) throw std::logic_error("schedule: worker " + std::to_string(id) + " reported a task it was not given");
  const Decision d = *w.task;
  if (d.kind == TaskKind::send) throw std::logic_error("schedule: a SEND ends with arrived(), not done()");
  w.task.reset();
  if (d.kind == TaskKind::merge) {
    w.incoming.erase(transfers_.at(d.transfer).order);
    transfers_.erase(d.transfer);
  } else if (d.kind == TaskKind::finished) {
    w.held.clear();
    complete_ = true;
    return;
  }
  if (!emptied) return;
  // Its surface is gone with every component of its leaves committed: they are finished, claimed
  // by nobody, and never sent, merged or re-done. What is on its way to it stays addressed to it.
  ++counts_.emptied;
  unclaim(id, w.held);
  for (NodeId leaf : w.held.leaves()) {
    taken_->change(leaf, -1);
    ++loose_;
    if (finished_[static_cast<std::size_t>(leaf)]) continue; // taken in by a batch: finished before
    finished_[static_cast<std::size_t>(leaf)] = 1;
    ++dropped_;
  }
  w.held.clear();
}

bool Schedule::arrived(WorkerId sender, TransferId t) {
  Worker& from = worker(sender);
  if (from.task && from.task->kind == TaskKind::send && from.task->transfer == t) from.task.reset();
  auto it = transfers_.find(t);
  if (it == transfers_.end()) return false; // its target died: the leaves are re-done
  if (it->second.from != sender || it->second.arrived)
    throw std::logic_error("schedule: transfer " + std::to_string(t) + " is not on its way from worker " +
                           std::to_string(sender));
  it->second.arrived = true;
  if (!it->second.merging) worker(it->second.to).ready.insert(it->second.order);
  return true;
}

void Schedule::release(const Aggregate& leaves, std::vector<NodeId>& out) {
  for (NodeId leaf : leaves.leaves()) {
    if (finished_[static_cast<std::size_t>(leaf)]) { // a batch took it in: claimed by nobody again, not re-done
      if (taken_->total(leaf) != 0) {
        taken_->change(leaf, -1);
        ++loose_;
      }
      continue;
    }
    if (unprocessed_[static_cast<std::size_t>(leaf)]) continue;
    unprocessed_[static_cast<std::size_t>(leaf)] = 1;
    ++unprocessed_count_;
    open_->change(leaf, +1);
    taken_->change(leaf, -1);
    out.push_back(leaf);
    ++counts_.redone_leaves;
  }
}

std::vector<NodeId> Schedule::leave(WorkerId id) {
  std::vector<NodeId> out;
  Worker& w = worker(id);
  if (!complete_) { // what it claims is no one's now (after the final pass nothing is claimed)
    for (const auto& [order, t] : w.incoming)
      if (!transfers_.at(t).merging) unclaim(id, transfers_.at(t).leaves);
    unclaim(id, w.held);
    for (const auto& [t, tr] : transfers_)
      if (tr.from == id && !tr.arrived && tr.to != id) unclaim(tr.to, tr.leaves);
  }
  release(w.held, out);
  // Surfaces addressed to it, and those it was still sending, are lost with it.
  for (auto it = transfers_.begin(); it != transfers_.end();) {
    Transfer& t = it->second;
    const bool to_it = t.to == id;
    const bool from_it = t.from == id && !t.arrived;
    if (!to_it && !from_it) {
      ++it;
      continue;
    }
    if (!t.merging) release(t.leaves, out); // a merging transfer's leaves are in w.held already
    if (!to_it) {
      worker(t.to).incoming.erase(t.order);
      worker(t.to).ready.erase(t.order);
    }
    it = transfers_.erase(it);
  }
  workers_.erase(id);
  return out;
}

std::optional<WorkerId> Schedule::transfer_target(TransferId t) const {
  auto it = transfers_.find(t);
  if (it == transfers_.end()) return std::nullopt;
  return it->second.to;
}

std::optional<WorkerId> Schedule::transfer_source(TransferId t) const {
  auto it = transfers_.find(t);
  if (it == transfers_.end()) return std::nullopt;
  return it->second.from;
}

std::size_t Schedule::transfer_leaves(TransferId t) const {
  auto it = transfers_.find(t);
  return it == transfers_.end() ? 0 : it->second.leaves.size();
}

std::size_t Schedule::unprocessed() const {
  return unprocessed_count_;
}

std::vector<NodeId> Schedule::take_unrecorded(WorkerId id) {
  auto it = workers_.find(id);
  return it == workers_.end() ? std::vector<NodeId>{} : std::exchange(it->second.fresh, {});
}

std::vector<NodeId> Schedule::held(WorkerId id) const {
  auto it = workers_.find(id);
  return it == workers_.end() ? std::vector<NodeId>{} : it->second.held.leaves();
}

std::size_t Schedule::leaves_held(WorkerId id) const {
  auto it = workers_.find(id);
  return it == workers_.end() ? 0 : it->second.held.size();
}

} // namespace geotandem::runtime
