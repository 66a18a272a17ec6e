// Aggregates of leaves and their restricted adjacency (aggregate.hpp).
#include "geotandem/runtime/aggregate.hpp"

#include <string>

#include "geotandem/core/error.hpp"

namespace geotandem::runtime {

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

bool nodes_adjacent(const BlockTree& tree, NodeId a, NodeId b) {
  if (a == tree.root() || b == tree.root()) return false;
  const NodeId ba = tree.brother(a), bb = tree.brother(b);
  if (tree.is_ancestor(ba, b)) return tree.restricted_adjacent(a, b);
  if (tree.is_ancestor(bb, a)) return tree.restricted_adjacent(b, a);
  return false;
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

} // namespace geotandem::runtime
