// The schedule of main before issue 55 (reference_schedule.hpp), verbatim but for its namespace.
#include "reference_schedule.hpp"

#include <stdexcept>
#include <string>

#include "geotandem/core/error.hpp"
#include "geotandem/runtime/aggregate.hpp"

namespace geotandem::runtime::reference {

using runtime::nodes_adjacent;
using tandem::BlockTree;
using tandem::kNoNode;
using tandem::NodeId;

Aggregate::Aggregate(const BlockTree& tree) : tree_(&tree), leaf_(tree.size(), 0) {
  auto is_leaf = std::make_shared<std::vector<char>>(tree.size(), 0);
  for (NodeId leaf : tree.leaves())
    (*is_leaf)[static_cast<std::size_t>(leaf)] = 1;
  is_leaf_ = std::move(is_leaf);
}

bool Aggregate::holds(NodeId leaf) const {
  return leaf >= 0 && static_cast<std::size_t>(leaf) < leaf_.size() && leaf_[static_cast<std::size_t>(leaf)];
}

void Aggregate::add(NodeId leaf) {
  if (leaf < 0 || static_cast<std::size_t>(leaf) >= leaf_.size() || !(*is_leaf_)[static_cast<std::size_t>(leaf)])
    throw InvalidArgument("aggregate: node " + std::to_string(leaf) + " is not a leaf of the block tree");
  char& held = leaf_[static_cast<std::size_t>(leaf)];
  if (!held) ++count_;
  held = 1;
}

void Aggregate::add(const Aggregate& other) {
  for (NodeId leaf : other.leaves())
    add(leaf);
}

void Aggregate::clear() {
  std::fill(leaf_.begin(), leaf_.end(), 0);
  count_ = 0;
}

std::vector<NodeId> Aggregate::leaves() const {
  std::vector<NodeId> out;
  for (NodeId leaf : tree_->leaves())
    if (leaf_[static_cast<std::size_t>(leaf)]) out.push_back(leaf);
  return out;
}

std::vector<NodeId> Aggregate::maximal_nodes() const {
  // Nodes are numbered so that a child comes after its parent: complete bottom-up in reverse order.
  const auto& nodes = tree_->nodes();
  std::vector<char> complete(nodes.size(), 0);
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const tandem::BlockNode& n = nodes[i];
    complete[i] = n.is_leaf() ? leaf_[i]
                              : static_cast<char>(complete[static_cast<std::size_t>(n.children[0])] &&
                                                  complete[static_cast<std::size_t>(n.children[1])]);
  }
  std::vector<NodeId> out;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const NodeId parent = nodes[i].parent;
    if (complete[i] && (parent == kNoNode || !complete[static_cast<std::size_t>(parent)]))
      out.push_back(static_cast<NodeId>(i));
  }
  return out;
}

bool Aggregate::adjacent(const Aggregate& other) const {
  if (empty() || other.empty()) return false;
  const std::vector<NodeId> mine = maximal_nodes(), theirs = other.maximal_nodes();
  for (NodeId a : mine)
    for (NodeId b : theirs)
      if (nodes_adjacent(*tree_, a, b)) return true;
  return false;
}

bool Aggregate::adjacent(NodeId node) const {
  for (NodeId a : maximal_nodes())
    if (nodes_adjacent(*tree_, a, node)) return true;
  return false;
}

Schedule::Schedule(const tandem::BlockTree& tree) : tree_(tree), unprocessed_(tree.size(), 0) {
  for (NodeId leaf : tree.leaves())
    unprocessed_[static_cast<std::size_t>(leaf)] = 1;
}

void Schedule::skip(NodeId leaf) {
  if (started_) throw std::logic_error("schedule: skip() after the first decision");
  if (leaf < 0 || static_cast<std::size_t>(leaf) >= tree_.size() || !tree_.node(leaf).is_leaf())
    throw InvalidArgument("schedule: node " + std::to_string(leaf) + " is not a leaf of the block tree");
  if (unprocessed_[static_cast<std::size_t>(leaf)]) ++skipped_;
  unprocessed_[static_cast<std::size_t>(leaf)] = 0;
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
  for (TransferId t : w.incoming)
    all.add(transfers_.at(t).leaves);
  return all;
}

// has_neighbor_worker: the live worker, other than this one, whose claimed leaves are
// restricted-adjacent to this one's and at least as many; the one claiming most leaves first.
std::optional<WorkerId> Schedule::neighbor(WorkerId id) {
  const Aggregate& mine = worker(id).held;
  std::optional<WorkerId> best;
  std::size_t best_size = 0;
  for (const auto& [other, w] : workers_) {
    if (other == id || w.retiring) continue;
    const Aggregate theirs = claimed(w);
    // The smaller side travels: a worker does not send to a smaller neighbour (that one sends to
    // it when it asks), so large aggregates stay put and their workers go on extracting.
    if (!theirs.empty() && theirs.size() >= mine.size() && mine.adjacent(theirs) && theirs.size() > best_size) {
      best = other;
      best_size = theirs.size();
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
    const std::size_t theirs = claimed(w).size();
    if (theirs > 0 && theirs >= mine && theirs > best_size) {
      best = other;
      best_size = theirs;
    }
  }
  return best;
}

// has_unprocessed_block: one restricted-adjacent to the worker's aggregate first, any otherwise.
NodeId Schedule::unprocessed_leaf(const Worker& w) const {
  NodeId any = kNoNode;
  const std::vector<NodeId> mine = w.held.maximal_nodes();
  for (NodeId leaf : tree_.leaves()) {
    if (!unprocessed_[static_cast<std::size_t>(leaf)]) continue;
    if (any == kNoNode) any = leaf;
    if (mine.empty()) break;
    for (NodeId a : mine)
      if (nodes_adjacent(tree_, a, leaf)) return leaf;
  }
  return any;
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
  transfers_.emplace(t, Transfer{.from = id, .to = target, .leaves = w.held});
  worker(target).incoming.push_back(t);
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
    const Aggregate theirs = claimed(w);
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
void Schedule::redirect_incoming(WorkerId id) {
  Worker& w = worker(id);
  for (auto it = w.incoming.begin(); it != w.incoming.end();) {
    Transfer& tr = transfers_.at(*it);
    const std::optional<WorkerId> v = tr.merging ? std::nullopt : successor(tr.leaves, id);
    if (!v) {
      ++it;
      continue;
    }
    tr.to = *v;
    worker(*v).incoming.push_back(*it);
    it = w.incoming.erase(it);
  }
}

Decision Schedule::next_retiring(WorkerId id, Worker& w) {
  redirect_incoming(id); // a successor may have joined since
  for (TransferId t : w.incoming) {
    Transfer& tr = transfers_.at(t);
    if (tr.arrived && !tr.merging) { // nobody else to take it: merged here, then handed back
      tr.merging = true;
      w.held.add(tr.leaves);
      return assign(w, {.kind = TaskKind::merge, .transfer = t});
    }
  }
  if (!w.incoming.empty()) return assign(w, {.kind = TaskKind::wait});
  if (!w.held.empty()) {
    if (const std::optional<WorkerId> v = successor(w.held, id)) {
      ++counts_.handback;
      return send_to(id, w, *v);
    }
    // Nobody to take it, and it holds the whole surface: it finishes the run itself rather than
    // have everything re-done.
    if (transfers_.empty() && w.held.size() == tree_.leaves().size() - skipped_ - dropped_)
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
  for (TransferId t : w.incoming) {
    Transfer& tr = transfers_.at(t);
    if (tr.arrived && !tr.merging) {
      tr.merging = true;
      w.held.add(tr.leaves);
      return assign(w, {.kind = TaskKind::merge, .transfer = t});
    }
  }
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
    w.held.add(leaf);
    return assign(w, {.kind = TaskKind::extract, .leaf = leaf});
  }

  if (skipped_ + dropped_ > 0 && !w.held.empty() && unprocessed() == 0)
    if (const std::optional<WorkerId> v = any_holder(id)) return send_to(id, w, *v);

  if (skipped_ + dropped_ == tree_.leaves().size()) { // a resumed run with nothing left to do
    complete_ = true;
    return assign(w, {.kind = TaskKind::finished});
  }
  // 4. The whole surface in one worker, nothing on its way: it finishes the run.
  if (transfers_.empty() && !w.held.empty() && w.held.size() == tree_.leaves().size() - skipped_ - dropped_)
    return assign(w, {.kind = TaskKind::finished, .final = true});
  return assign(w, {.kind = TaskKind::wait});
}

void Schedule::done(WorkerId id, bool emptied) {
  Worker& w = worker(id);
  if (!w.task) throw std::logic_error("schedule: worker " + std::to_string(id) + " reported a task it was not given");
  const Decision d = *w.task;
  if (d.kind == TaskKind::send) throw std::logic_error("schedule: a SEND ends with arrived(), not done()");
  w.task.reset();
  if (d.kind == TaskKind::merge) {
    transfers_.erase(d.transfer);
    std::erase(w.incoming, d.transfer);
  } else if (d.kind == TaskKind::finished) {
    w.held.clear();
    complete_ = true;
    return;
  }
  // Added for issue 55's empty surfaces, in this schedule's own terms: the leaves held are finished
  // (counted with the skipped ones in every test above) and held by nobody.
  if (emptied) {
    dropped_ += w.held.size();
    w.held.clear();
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
  return true;
}

void Schedule::release(const Aggregate& leaves, std::vector<NodeId>& out) {
  for (NodeId leaf : leaves.leaves()) {
    unprocessed_[static_cast<std::size_t>(leaf)] = 1;
    out.push_back(leaf);
    ++counts_.redone_leaves;
  }
}

std::vector<NodeId> Schedule::leave(WorkerId id) {
  std::vector<NodeId> out;
  Worker& w = worker(id);
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
    if (!to_it) std::erase(worker(t.to).incoming, it->first);
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
  std::size_t n = 0;
  for (NodeId leaf : tree_.leaves())
    n += unprocessed_[static_cast<std::size_t>(leaf)] ? 1u : 0u;
  return n;
}

std::vector<NodeId> Schedule::held(WorkerId id) const {
  auto it = workers_.find(id);
  return it == workers_.end() ? std::vector<NodeId>{} : it->second.held.leaves();
}

std::size_t Schedule::leaves_held(WorkerId id) const {
  auto it = workers_.find(id);
  return it == workers_.end() ? 0 : it->second.held.size();
}

} // namespace geotandem::runtime::reference
