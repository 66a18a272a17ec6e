// Leaf counts per node and face (leaf_counts.hpp).
#include "leaf_counts.hpp"

namespace geotandem::runtime::detail {

using tandem::kNoNode;
using tandem::NodeId;

void LeafCounts::count_every_leaf() {
  const auto& nodes = tree_.nodes();
  for (std::size_t i = nodes.size(); i-- > 0;) { // children come after their parent
    const tandem::BlockNode& n = nodes[i];
    auto& c = counts_[i];
    if (n.is_leaf()) {
      c.fill(1);
      continue;
    }
    const auto& low = counts_[index(n.children[0])];
    const auto& high = counts_[index(n.children[1])];
    for (std::size_t k = 0; k < c.size(); ++k)
      c[k] = low[k] + high[k];
    // Across the cut's axis only one child touches each face.
    c[2 * static_cast<std::size_t>(n.split_axis)] = low[2 * static_cast<std::size_t>(n.split_axis)];
    c[2 * static_cast<std::size_t>(n.split_axis) + 1] = high[2 * static_cast<std::size_t>(n.split_axis) + 1];
  }
}

void LeafCounts::change(NodeId leaf, int delta) {
  const volume::Box& cells = tree_.node(leaf).cells;
  for (NodeId x = leaf; x != kNoNode; x = tree_.node(x).parent) {
    const volume::Box& box = tree_.node(x).cells;
    auto& c = counts_[index(x)];
    c[kTotal] = static_cast<std::uint32_t>(static_cast<std::int64_t>(c[kTotal]) + delta);
    for (int axis = 0; axis < 3; ++axis) {
      auto& low = c[2 * static_cast<std::size_t>(axis)];
      auto& high = c[2 * static_cast<std::size_t>(axis) + 1];
      if (cells.lo[axis] == box.lo[axis]) low = static_cast<std::uint32_t>(static_cast<std::int64_t>(low) + delta);
      if (cells.hi[axis] == box.hi[axis]) high = static_cast<std::uint32_t>(static_cast<std::int64_t>(high) + delta);
    }
  }
}

NodeId LeafCounts::first(NodeId node, int axis, int side) const {
  if (count(node, axis, side) == 0) return kNoNode;
  NodeId x = node;
  // A child of a cut along `axis` touches the face only on its side; a child of a cut along
  // another axis touches it where its parent does, so a leaf on the child's face is on x's.
  while (!tree_.node(x).is_leaf()) {
    const tandem::BlockNode& n = tree_.node(x);
    if (axis >= 0 && n.split_axis == axis)
      x = n.children[static_cast<std::size_t>(side)];
    else
      x = count(n.children[0], axis, side) > 0 ? n.children[0] : n.children[1];
  }
  return x;
}

std::array<int, 2> LeafCounts::face_towards(const tandem::BlockTree& tree, NodeId a) {
  const tandem::BlockNode& parent = tree.node(tree.node(a).parent);
  return {parent.split_axis, parent.children[0] == a ? 0 : 1};
}

} // namespace geotandem::runtime::detail
