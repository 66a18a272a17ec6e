// Aggregates of leaves and their restricted adjacency (aggregate.hpp).
#include "geotandem/runtime/aggregate.hpp"

#include <string>

#include "geotandem/core/error.hpp"

namespace geotandem::runtime {

using tandem::BlockTree;
using tandem::kNoNode;
using tandem::NodeId;

NodeId subtree_end(const BlockTree& tree, NodeId node) {
  // The subtree ends where the next node that is not a descendant starts: the high brother of the
  // lowest ancestor (or the node itself) that is a low child.
  for (NodeId x = node; x != tree.root(); x = tree.node(x).parent) {
    const tandem::BlockNode& parent = tree.node(tree.node(x).parent);
    if (parent.children[0] == x) return parent.children[1];
  }
  return static_cast<NodeId>(tree.size());
}

bool Aggregate::covers(NodeId node) const {
  for (NodeId x = node; x != kNoNode; x = tree_->node(x).parent)
    if (maximal_.count(x)) return true;
  return false;
}

bool Aggregate::inside(NodeId node) const {
  const auto it = maximal_.upper_bound(node);
  return it != maximal_.end() && it->first < subtree_end(*tree_, node);
}

bool Aggregate::holds(NodeId leaf) const {
  return leaf >= 0 && static_cast<std::size_t>(leaf) < tree_->size() && covers(leaf);
}

void Aggregate::add_node(NodeId node, std::size_t leaves) {
  // A brother held whole is a maximal node (its parent was not complete): the two make the parent.
  while (node != tree_->root()) {
    const auto brother = maximal_.find(tree_->brother(node));
    if (brother == maximal_.end()) break;
    leaves += brother->second;
    maximal_.erase(brother);
    node = tree_->node(node).parent;
  }
  maximal_.emplace(node, leaves);
}

void Aggregate::add(NodeId leaf) {
  if (leaf < 0 || static_cast<std::size_t>(leaf) >= tree_->size() || !tree_->node(leaf).is_leaf())
    throw InvalidArgument("aggregate: node " + std::to_string(leaf) + " is not a leaf of the block tree");
  if (covers(leaf)) return;
  add_node(leaf, 1);
  ++count_;
}

void Aggregate::add(const Aggregate& other) {
  for (const auto& [node, leaves] : other.maximal_) {
    if (covers(node)) continue;
    if (inside(node)) { // overlapping: leaf by leaf (the schedule never gets here)
      Aggregate part(*tree_);
      part.add_node(node, leaves);
      part.count_ = leaves;
      for (NodeId leaf : part.leaves())
        add(leaf);
      continue;
    }
    add_node(node, leaves);
    count_ += leaves;
  }
}

std::vector<NodeId> Aggregate::leaves() const {
  std::vector<NodeId> out;
  out.reserve(count_);
  std::vector<NodeId> stack;
  for (const auto& [node, leaves] : maximal_) {
    stack.push_back(node);
    while (!stack.empty()) { // depth first, low child first: tree order
      const tandem::BlockNode& n = tree_->node(stack.back());
      stack.pop_back();
      if (n.is_leaf()) {
        out.push_back(n.id);
      } else {
        stack.push_back(n.children[1]);
        stack.push_back(n.children[0]);
      }
    }
  }
  return out;
}

std::vector<NodeId> Aggregate::maximal_nodes() const {
  std::vector<NodeId> out;
  out.reserve(maximal_.size());
  for (const auto& [node, leaves] : maximal_)
    out.push_back(node);
  return out;
}

bool nodes_adjacent(const BlockTree& tree, NodeId a, NodeId b) {
  if (a == tree.root() || b == tree.root()) return false;
  const NodeId ba = tree.brother(a), bb = tree.brother(b);
  if (tree.is_ancestor(ba, b)) return tree.restricted_adjacent(a, b);
  if (tree.is_ancestor(bb, a)) return tree.restricted_adjacent(b, a);
  return false;
}

// A pair (a of this, b of other) with a in the subtree of brother(b): b is the brother of a or of
// one of a's ancestors. Walking up from each a finds every such b without looking at the others.
bool Aggregate::touched_by(const Aggregate& other) const {
  for (const auto& [a, leaves] : maximal_)
    for (NodeId c = a; c != tree_->root(); c = tree_->node(c).parent) {
      const NodeId b = tree_->brother(c);
      if (other.maximal_.count(b) && tree_->restricted_adjacent(b, a)) return true;
    }
  return false;
}

bool Aggregate::adjacent(const Aggregate& other) const {
  if (empty() || other.empty()) return false;
  return touched_by(other) || other.touched_by(*this);
}

bool Aggregate::adjacent(NodeId node) const {
  if (empty()) return false;
  Aggregate single(*tree_);
  single.maximal_.emplace(node, 1);
  single.count_ = 1;
  return touched_by(single) || single.touched_by(*this);
}

} // namespace geotandem::runtime
