// The manager's decisions, algorithm 6 of the seed (schedule.hpp).
#include "geotandem/runtime/schedule.hpp"

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

Schedule::Schedule(const tandem::BlockTree& tree)
    : tree_(tree), unprocessed_(tree.size(), 0), unprocessed_count_(tree.leaves().size()),
      open_(std::make_unique<detail::LeafCounts>(tree)), taken_(std::make_unique<detail::LeafCounts>(tree)),
      owner_(tree.size(), 0) {
  for (NodeId leaf : tree.leaves())
    unprocessed_[static_cast<std::size_t>(leaf)] = 1;
  open_->count_every_leaf();
}

Schedule::~Schedule() = default;

// A node of which `id` claims every leaf, none before: it becomes a maximal node of the worker's
// claim, merged with its brother when that one is claimed whole too.
void Schedule::claim_node(WorkerId id, NodeId node) {
  while (node != tree_.root()) {
    const auto brother = static_cast<std::size_t>(tree_.brother(node));
    if (owner_[brother] != id) break;
    owner_[brother] = 0;
    node = tree_.node(node).parent;
  }
  owner_[static_cast<std::size_t>(node)] = id;
}

// A node of which `id` claims every leaf stops being claimed: the maximal node above it is split
// into the brothers of the path down to it.
void Schedule::unclaim_node(WorkerId id, NodeId node) {
  NodeId top = node;
  while (top != kNoNode && owner_[static_cast<std::size_t>(top)] != id)
    top = tree_.node(top).parent;
  if (top == kNoNode)
    throw std::logic_error("schedule: worker " + std::to_string(id) + " does not claim " + tree_.describe(node));
  owner_[static_cast<std::size_t>(top)] = 0;
  for (NodeId x = node; x != top; x = tree_.node(x).parent)
    owner_[static_cast<std::size_t>(tree_.brother(x))] = id;
}

void Schedule::claim(WorkerId id, const Aggregate& leaves) {
  for (const auto& [node, n] : leaves.maximal())
    claim_node(id, node);
  worker(id).claimed += leaves.size();
}

void Schedule::unclaim(WorkerId id, const Aggregate& leaves) {
  for (const auto& [node, n] : leaves.maximal())
    unclaim_node(id, node);
  Worker& w = worker(id);
  w.claimed -= std::min(w.claimed, leaves.size());
}

void Schedule::move_claim(const Aggregate& leaves, WorkerId from, WorkerId to) {
  unclaim(from, leaves);
  claim(to, leaves);
}

void Schedule::owners_on_face(NodeId node, int axis, int side, WorkerId id, std::vector<WorkerId>& out) const {
  std::vector<NodeId> stack{node};
  while (!stack.empty()) {
    const NodeId x = stack.back();
    stack.pop_back();
    if (const WorkerId v = owner_[static_cast<std::size_t>(x)]) {
      if (v != id) out.push_back(v);
      continue;
    }
    const tandem::BlockNode& n = tree_.node(x);
    if (n.is_leaf() || taken_->on_face(x, axis, side) == 0) continue;
    if (n.split_axis == axis) {
      stack.push_back(n.children[static_cast<std::size_t>(side)]);
    } else {
      stack.push_back(n.children[1]);
      stack.push_back(n.children[0]);
    }
  }
}

void Schedule::skip(NodeId leaf) {
  if (started_) throw std::logic_error("schedule: skip() after the first decision");
  if (leaf < 0 || static_cast<std::size_t>(leaf) >= tree_.size() || !tree_.node(leaf).is_leaf())
    throw InvalidArgument("schedule: node " + std::to_string(leaf) + " is not a leaf of the block tree");
  if (!unprocessed_[static_cast<std::size_t>(leaf)]) return;
  ++skipped_;
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

// has_neighbor_worker: the live worker, other than this one, whose claimed leaves are
// restricted-adjacent to this one's and at least as many; the one claiming most leaves first (the
// lowest id among equals). The candidates come from the owners of the nodes next to each maximal
// node a of this worker: inside brother(a) on its face towards a, and the brothers of a and of its
// ancestors (aggregate.cpp explains the two directions of the test).
std::optional<WorkerId> Schedule::neighbor(WorkerId id) {
  const Aggregate& mine = worker(id).held;
  std::vector<WorkerId> found;
  for (const auto& [a, n] : mine.maximal()) {
    if (a == tree_.root()) continue;
    const auto [axis, side] = detail::LeafCounts::face_towards(tree_, a);
    owners_on_face(tree_.brother(a), axis, side, id, found);
    for (NodeId c = a; c != tree_.root(); c = tree_.node(c).parent) {
      const NodeId b = tree_.brother(c);
      const WorkerId v = owner_[static_cast<std::size_t>(b)];
      if (v != 0 && v != id && tree_.restricted_adjacent(b, a)) found.push_back(v);
    }
  }
  std::optional<WorkerId> best;
  std::size_t best_size = 0;
  for (WorkerId other : found) {
    const Worker& w = workers_.at(other);
    if (w.retiring) continue;
    // The smaller side travels: a worker does not send to a smaller neighbour (that one sends to
    // it when it asks), so large aggregates stay put and their workers go on extracting.
    const std::size_t theirs = w.claimed;
    if (theirs > 0 && theirs >= mine.size() && (theirs > best_size || (theirs == best_size && other < *best))) {
      best = other;
      best_size = theirs;
    }
  }
  return best;
}

// After a resume, skipped leaves can leave gaps between the aggregates that the restricted
// adjacency never bridges: once nothing is left to extract, a worker hands its surface to the
// worker holding most leaves (at least as many as its own), adjacent or not. Merging surfaces that
// do not touch is valid (the region becomes their union).
std::optional<WorkerId> Schedule::any_holder(WorkerId id) const {
  const std::size_t mine = workers_.at(id).held.size();
  std::optional<WorkerId> best;
  std::size_t best_size = 0;
  for (const auto& [other, w] : workers_) {
    if (other == id || w.retiring) continue;
    const std::size_t theirs = w.claimed;
    if (theirs > 0 && theirs >= mine && theirs > best_size) {
      best = other;
      best_size = theirs;
    }
  }
  return best;
}

// has_unprocessed_block: the first (in tree order) restricted-adjacent to the worker's aggregate,
// the first of all otherwise. For each maximal node a of the aggregate: the first unprocessed leaf
// of brother(a) on its face towards a, and the brothers of a and of its ancestors that are
// unprocessed leaves passing the test.
NodeId Schedule::unprocessed_leaf(const Worker& w) const {
  NodeId best = kNoNode;
  const auto better = [&](NodeId leaf) { return leaf != kNoNode && (best == kNoNode || leaf < best); };
  for (const auto& [a, n] : w.held.maximal()) {
    if (a == tree_.root()) continue;
    const auto [axis, side] = detail::LeafCounts::face_towards(tree_, a);
    if (const NodeId leaf = open_->first(tree_.brother(a), axis, side); better(leaf)) best = leaf;
    for (NodeId c = a; c != tree_.root(); c = tree_.node(c).parent) {
      const NodeId b = tree_.brother(c);
      if (better(b) && unprocessed_[static_cast<std::size_t>(b)] && tree_.restricted_adjacent(b, a)) best = b;
    }
  }
  return best != kNoNode ? best : open_->first(tree_.root());
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
    if (transfers_.empty() && w.held.size() == tree_.leaves().size() - skipped_)
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
    unprocessed_[static_cast<std::size_t>(leaf)] = 0;
    --unprocessed_count_;
    open_->change(leaf, -1);
    taken_->change(leaf, +1);
    w.held.add(leaf);
    w.fresh.push_back(leaf);
    claim_node(id, leaf);
    ++w.claimed;
    return assign(w, {.kind = TaskKind::extract, .leaf = leaf});
  }

  if (skipped_ > 0 && !w.held.empty() && unprocessed() == 0)
    if (const std::optional<WorkerId> v = any_holder(id)) return send_to(id, w, *v);

  if (skipped_ == tree_.leaves().size()) { // a resumed run with nothing left to do
    complete_ = true;
    return assign(w, {.kind = TaskKind::finished});
  }
  // 4. The whole surface in one worker, nothing on its way: it finishes the run.
  if (transfers_.empty() && !w.held.empty() && w.held.size() == tree_.leaves().size() - skipped_)
    return assign(w, {.kind = TaskKind::finished, .final = true});
  return assign(w, {.kind = TaskKind::wait});
}

void Schedule::done(WorkerId id) {
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
  }
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
