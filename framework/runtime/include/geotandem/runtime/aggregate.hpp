#pragma once
// An aggregate: the set of leaves of the block tree whose partial surfaces one worker holds (or
// will hold once the surfaces addressed to it are merged). The seed's restricted-adjacency test
// (section 3.2) relates tree nodes; an aggregate is described by its maximal complete nodes (the
// nodes all of whose leaves it holds, whose parent it does not hold whole), and two aggregates are
// neighbours when a maximal node of one and a maximal node of the other pass the test.
#include <cstddef>
#include <memory>
#include <vector>

#include "geotandem/tandem/block_tree.hpp"

namespace geotandem::runtime {

class Aggregate {
public:
  // An empty aggregate over `tree`'s leaves. `tree` must outlive it.
  explicit Aggregate(const tandem::BlockTree& tree);

  bool empty() const { return count_ == 0; }
  std::size_t size() const { return count_; } // leaves held
  bool holds(tandem::NodeId leaf) const;
  // Throws InvalidArgument when `leaf` is not a leaf of the tree.
  void add(tandem::NodeId leaf);
  void add(const Aggregate& other);
  void clear();
  // The leaves held, in tree order.
  std::vector<tandem::NodeId> leaves() const;

  // The maximal complete nodes (see above), in tree order.
  std::vector<tandem::NodeId> maximal_nodes() const;
  // The seed's restricted adjacency between two aggregates: some maximal node a of this one and b
  // of `other` with b in the subtree of brother(a) and restricted_adjacent(a, b), or the same with
  // the roles swapped. False when either is empty.
  bool adjacent(const Aggregate& other) const;
  // The same test against a single node (a leaf that is not processed yet).
  bool adjacent(tandem::NodeId node) const;

private:
  const tandem::BlockTree* tree_;
  std::vector<char> leaf_; // per node id: 1 when the node is a leaf held here
  // Per node id: 1 for a leaf, shared by every aggregate of the tree.
  std::shared_ptr<const std::vector<char>> is_leaf_;
  std::size_t count_ = 0;
};

// True when the tree nodes a and b (disjoint subtrees) pass the seed's restricted adjacency in one
// direction or the other.
bool nodes_adjacent(const tandem::BlockTree& tree, tandem::NodeId a, tandem::NodeId b);

} // namespace geotandem::runtime
