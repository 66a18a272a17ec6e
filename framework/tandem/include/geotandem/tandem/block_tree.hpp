#pragma once
// The binary block tree of the seed (section 3.2): the cube's cells split recursively in two,
// perpendicular to the longest axis, while a block is larger than the leaf size. Node types say
// on which side of its parent's cut a node lies; the restricted-adjacency test uses them to tell,
// without geometry, whether a nephew shares a face with a node.
//
// Units: boxes are boxes of CELLS in index space ([lo, hi) per axis; cell (i, j, k) spans samples
// i..i+1, ...), so a node of cells [lo, hi) covers the index-coordinate region [lo, hi] and reads
// samples [lo, hi + 1). Two nodes that share a face share the sample plane on it.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "geotandem/volume/box.hpp"

namespace geotandem::tandem {

// A cut along axis 0 (x, i) makes a left and a right child, along axis 1 (y, j) up and down,
// along axis 2 (z, k) front and back. The first child listed is always the low side.
enum class NodeType : std::uint8_t { root, left, right, up, down, front, back };

// The type on the other side of the same cut (left <-> right, up <-> down, front <-> back);
// root for root.
NodeType opposite(NodeType type);
const char* to_string(NodeType type);
// The axis of the cut that made a node of this type (-1 for root).
int cut_axis(NodeType type);

using NodeId = std::int32_t;
inline constexpr NodeId kNoNode = -1;

struct BlockNode {
  NodeId id = kNoNode;
  NodeId parent = kNoNode;
  std::array<NodeId, 2> children{kNoNode, kNoNode}; // low side first; both kNoNode for a leaf
  NodeType type = NodeType::root;
  int split_axis = -1; // axis the node is cut along; -1 for a leaf
  int depth = 0;       // 0 for the root
  volume::Box cells;

  bool is_leaf() const { return children[0] == kNoNode; }
};

// Which faces of a node's box are open (inside the cube, so a neighbour block lies behind them)
// rather than faces of the whole cube. low[a] is the face at cells.lo[a], high[a] at cells.hi[a].
struct OpenFaces {
  std::array<bool, 3> low{false, false, false};
  std::array<bool, 3> high{false, false, false};

  bool any() const { return low[0] || low[1] || low[2] || high[0] || high[1] || high[2]; }
  bool operator==(const OpenFaces&) const = default;
};

class BlockTree {
public:
  // Splits `cube` (the cube's cells, e.g. cube_cells(shape)) while a block has more than
  // `leaf_size` cells along some axis. The cut is perpendicular to the block's longest axis (the
  // lowest such axis on ties) at lo + size / 2. Throws InvalidArgument when the box is empty or
  // leaf_size < 1.
  BlockTree(const volume::Box& cube, std::int64_t leaf_size);

  const volume::Box& cube() const { return nodes_.front().cells; }
  std::int64_t leaf_size() const { return leaf_size_; }
  NodeId root() const { return 0; }
  std::size_t size() const { return nodes_.size(); }
  // Throws InvalidArgument for an id that is not a node of this tree.
  const BlockNode& node(NodeId id) const;
  const std::vector<BlockNode>& nodes() const { return nodes_; }
  // Leaves from the low side to the high side of every cut (depth-first, first child first).
  const std::vector<NodeId>& leaves() const { return leaves_; }

  // The other child of the node's parent; kNoNode for the root.
  NodeId brother(NodeId id) const;
  // True when `ancestor` is `id` itself or one of its ancestors.
  bool is_ancestor(NodeId ancestor, NodeId id) const;
  // The leaf whose box holds the cell; kNoNode when the cell is outside the cube.
  NodeId leaf_of(const volume::Index3& cell) const;

  // The seed's restricted adjacency: may `n`, in the subtree of p2 = brother(p1), be merged with
  // p1? True iff every node from n up to, but excluding, p2 has a type other than
  // opposite(type(p1)); true for n == p2 (brothers share their parent's cut). Geometrically:
  // n's box shares a face of positive area with p1's box.
  // Throws InvalidArgument when p1 is the root or n is not in the subtree of brother(p1).
  bool restricted_adjacent(NodeId p1, NodeId n) const;

  OpenFaces open_faces(NodeId id) const;

  // "node 5 (right, depth 2) [0:64, 64:128, 0:128]", for messages.
  std::string describe(NodeId id) const;

private:
  void split(NodeId id);

  std::vector<BlockNode> nodes_;
  std::vector<NodeId> leaves_;
  std::int64_t leaf_size_ = 0;
};

// True when two boxes touch along a face of positive area (and do not overlap).
bool boxes_share_face(const volume::Box& a, const volume::Box& b);

} // namespace geotandem::tandem
