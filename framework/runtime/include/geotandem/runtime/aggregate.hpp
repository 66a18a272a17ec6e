#pragma once
// An aggregate: the set of leaves of the block tree whose partial surfaces one worker holds (or
// will hold once the surfaces addressed to it are merged). The seed's restricted-adjacency test
// (section 3.2) relates tree nodes; an aggregate is described by its maximal complete nodes (the
// nodes all of whose leaves it holds, whose parent it does not hold whole), and two aggregates are
// neighbours when a maximal node of one and a maximal node of the other pass the test.
//
// Cost: the aggregate keeps only its maximal nodes, so adding a leaf or a disjoint aggregate, and
// the tests below, cost O(depth log m) per maximal node (m of them), not O(size of the tree): the
// manager does them for every task (issue 55).
#include <cstddef>
#include <map>
#include <vector>

#include "geotandem/tandem/block_tree.hpp"

namespace geotandem::runtime {

class Aggregate {
public:
  // An empty aggregate over `tree`'s leaves. `tree` must outlive it.
  explicit Aggregate(const tandem::BlockTree& tree) : tree_(&tree) {}

  bool empty() const { return count_ == 0; }
  std::size_t size() const { return count_; } // leaves held
  bool holds(tandem::NodeId leaf) const;
  // Throws InvalidArgument when `leaf` is not a leaf of the tree.
  void add(tandem::NodeId leaf);
  void add(const Aggregate& other);
  void clear() {
    maximal_.clear();
    count_ = 0;
  }
  // The leaves held, in tree order.
  std::vector<tandem::NodeId> leaves() const;

  // The maximal complete nodes (see above), in tree order, with the number of leaves under each.
  const std::map<tandem::NodeId, std::size_t>& maximal() const { return maximal_; }
  std::vector<tandem::NodeId> maximal_nodes() const;
  // The seed's restricted adjacency between two aggregates: some maximal node a of this one and b
  // of `other` with b in the subtree of brother(a) and restricted_adjacent(a, b), or the same with
  // the roles swapped. False when either is empty.
  bool adjacent(const Aggregate& other) const;
  // The same test against a single node (a leaf that is not processed yet).
  bool adjacent(tandem::NodeId node) const;

private:
  // Adds a node none of whose leaves is held, with its `leaves`; merges brothers upwards.
  void add_node(tandem::NodeId node, std::size_t leaves);
  // True when `node` or an ancestor of it is a maximal node.
  bool covers(tandem::NodeId node) const;
  // True when a maximal node lies strictly inside `node`'s subtree.
  bool inside(tandem::NodeId node) const;
  // Whether a maximal node b of `other`, b = brother(c) for c an ancestor of one of this
  // aggregate's maximal nodes a (or a itself), passes restricted_adjacent(b, a).
  bool touched_by(const Aggregate& other) const;

  const tandem::BlockTree* tree_;
  std::map<tandem::NodeId, std::size_t> maximal_; // maximal node -> leaves under it
  std::size_t count_ = 0;
};

// True when the tree nodes a and b (disjoint subtrees) pass the seed's restricted adjacency in one
// direction or the other.
bool nodes_adjacent(const tandem::BlockTree& tree, tandem::NodeId a, tandem::NodeId b);

// One past the last node id of `node`'s subtree (ids are in depth-first order, a parent before
// its children, so a subtree is the id range [node, subtree_end)). O(depth).
tandem::NodeId subtree_end(const tandem::BlockTree& tree, tandem::NodeId node);

} // namespace geotandem::runtime
