// The schedule's claims and neighbours (schedule.hpp): which leaves each worker holds, kept as the
// worker's largest wholly claimed nodes with an owner per claimed node, and the neighbour a worker
// merges with, found through those owners and the per-node leaf counts.
#include "geotandem/runtime/schedule.hpp"

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "leaf_counts.hpp"

namespace geotandem::runtime {

using tandem::kNoNode;
using tandem::NodeId;

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

} // namespace geotandem::runtime
