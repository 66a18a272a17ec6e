// BlockTree: recursive binary split of the cube's cells and the restricted-adjacency test.

#include "geotandem/tandem/block_tree.hpp"

#include <algorithm>

#include "geotandem/core/error.hpp"

namespace geotandem::tandem {

NodeType opposite(NodeType type) {
  switch (type) {
  case NodeType::left: return NodeType::right;
  case NodeType::right: return NodeType::left;
  case NodeType::up: return NodeType::down;
  case NodeType::down: return NodeType::up;
  case NodeType::front: return NodeType::back;
  case NodeType::back: return NodeType::front;
  case NodeType::root: break;
  }
  return NodeType::root;
}

const char* to_string(NodeType type) {
  switch (type) {
  case NodeType::left: return "left";
  case NodeType::right: return "right";
  case NodeType::up: return "up";
  case NodeType::down: return "down";
  case NodeType::front: return "front";
  case NodeType::back: return "back";
  case NodeType::root: break;
  }
  return "root";
}

int cut_axis(NodeType type) {
  switch (type) {
  case NodeType::left:
  case NodeType::right: return 0;
  case NodeType::up:
  case NodeType::down: return 1;
  case NodeType::front:
  case NodeType::back: return 2;
  case NodeType::root: break;
  }
  return -1;
}

BlockTree::BlockTree(const volume::Box& cube, std::int64_t leaf_size) : leaf_size_(leaf_size) {
  if (cube.empty())
    throw InvalidArgument("cannot split the empty box of cells " + cube.to_string() + " into blocks", {},
                          "the cube needs at least 2 samples along each axis");
  if (leaf_size < 1)
    throw InvalidArgument("leaf size " + std::to_string(leaf_size) + " is not a positive number of cells", {},
                          "give the largest number of cells per axis of a leaf block, e.g. 128");
  BlockNode root;
  root.id = 0;
  root.cells = cube;
  nodes_.push_back(root);
  split(0);
}

void BlockTree::split(NodeId id) {
  // Recursion depth is the tree depth: about log2 of the number of leaves.
  const volume::Box box = nodes_[static_cast<std::size_t>(id)].cells;
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (box.size(a) > box.size(axis)) axis = a;
  if (box.size(axis) <= leaf_size_) {
    leaves_.push_back(id);
    return;
  }
  static constexpr NodeType low[3] = {NodeType::left, NodeType::up, NodeType::front};
  const std::int64_t cut = box.lo[axis] + box.size(axis) / 2;
  for (int side = 0; side < 2; ++side) {
    BlockNode child;
    child.id = static_cast<NodeId>(nodes_.size());
    child.parent = id;
    child.type = side == 0 ? low[axis] : opposite(low[axis]);
    child.depth = nodes_[static_cast<std::size_t>(id)].depth + 1;
    child.cells = box;
    (side == 0 ? child.cells.hi : child.cells.lo)[axis] = cut;
    nodes_[static_cast<std::size_t>(id)].children[side] = child.id;
    nodes_[static_cast<std::size_t>(id)].split_axis = axis;
    nodes_.push_back(child);
    split(child.id);
  }
}

const BlockNode& BlockTree::node(NodeId id) const {
  if (id < 0 || static_cast<std::size_t>(id) >= nodes_.size())
    throw InvalidArgument("no block node " + std::to_string(id) + " in a tree of " + std::to_string(nodes_.size()) +
                          " nodes");
  return nodes_[static_cast<std::size_t>(id)];
}

NodeId BlockTree::brother(NodeId id) const {
  const BlockNode& n = node(id);
  if (n.parent == kNoNode) return kNoNode;
  const BlockNode& p = node(n.parent);
  return p.children[0] == id ? p.children[1] : p.children[0];
}

bool BlockTree::is_ancestor(NodeId ancestor, NodeId id) const {
  node(ancestor);
  for (NodeId x = id; x != kNoNode; x = node(x).parent)
    if (x == ancestor) return true;
  return false;
}

NodeId BlockTree::leaf_of(const volume::Index3& cell) const {
  if (!cube().contains(cell)) return kNoNode;
  NodeId x = root();
  while (!node(x).is_leaf()) {
    const BlockNode& n = node(x);
    x = cell[n.split_axis] < node(n.children[0]).cells.hi[n.split_axis] ? n.children[0] : n.children[1];
  }
  return x;
}

bool BlockTree::restricted_adjacent(NodeId p1, NodeId n) const {
  const NodeId p2 = brother(p1);
  if (p2 == kNoNode) throw InvalidArgument("the root block " + describe(p1) + " has no brother to merge with");
  if (!is_ancestor(p2, n))
    throw InvalidArgument(describe(n) + " is not in the subtree of " + describe(p2) + ", the brother of " +
                              describe(p1),
                          {}, "restricted adjacency applies to a node's brother and its brother's descendants");
  const NodeType forbidden = opposite(node(p1).type);
  // Each node on the way up lies on one side of a cut of p2's subtree; a cut across p1's axis
  // that puts it on the far side (the type opposite to p1's) moves it away from p1's face.
  for (NodeId x = n; x != p2; x = node(x).parent)
    if (node(x).type == forbidden) return false;
  return true;
}

OpenFaces BlockTree::open_faces(NodeId id) const {
  const volume::Box& b = node(id).cells;
  OpenFaces out;
  for (int a = 0; a < 3; ++a) {
    out.low[a] = b.lo[a] > cube().lo[a];
    out.high[a] = b.hi[a] < cube().hi[a];
  }
  return out;
}

std::string BlockTree::describe(NodeId id) const {
  if (id < 0 || static_cast<std::size_t>(id) >= nodes_.size()) return "node " + std::to_string(id) + " (none)";
  const BlockNode& n = nodes_[static_cast<std::size_t>(id)];
  return "node " + std::to_string(id) + " (" + to_string(n.type) + ", depth " + std::to_string(n.depth) + ") " +
         n.cells.to_string();
}

bool boxes_share_face(const volume::Box& a, const volume::Box& b) {
  if (a.empty() || b.empty()) return false;
  int touching = -1;
  for (int axis = 0; axis < 3; ++axis) {
    const std::int64_t overlap = std::min(a.hi[axis], b.hi[axis]) - std::max(a.lo[axis], b.lo[axis]);
    if (overlap > 0) continue;
    if (overlap < 0 || touching != -1) return false; // apart, or touching along an edge or corner only
    touching = axis;
  }
  return touching != -1;
}

} // namespace geotandem::tandem
