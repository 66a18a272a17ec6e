#pragma once
// Per node of the block tree, how many of its leaves are in some state (unprocessed, say), in all
// and among those touching each of the node's six faces, kept up to date leaf by leaf in O(depth).
// The manager's schedule finds with it, in O(depth), the first such leaf of a subtree, or the first
// one touching a face of it (the seed's restricted adjacency: the leaves of brother(a) that share a
// face with a are those touching brother(a)'s face towards a). Internal to the runtime.
#include <array>
#include <cstdint>
#include <vector>

#include "geotandem/tandem/block_tree.hpp"

namespace geotandem::runtime::detail {

class LeafCounts {
public:
  explicit LeafCounts(const tandem::BlockTree& tree) : tree_(tree), counts_(tree.size()) {}

  // Every leaf counted, in O(size of the tree).
  void count_every_leaf();
  // `leaf` enters (+1) or leaves (-1) the state.
  void change(tandem::NodeId leaf, int delta);
  std::uint32_t total(tandem::NodeId node) const { return counts_[index(node)][kTotal]; }
  // Leaves counted under `node` whose box touches its face on `axis` at the low (side 0) or high
  // (side 1) end.
  std::uint32_t on_face(tandem::NodeId node, int axis, int side) const {
    return counts_[index(node)][2 * static_cast<std::size_t>(axis) + static_cast<std::size_t>(side)];
  }
  // The first counted leaf of `node`'s subtree in tree order (kNoNode when none); with axis >= 0,
  // the first one touching `node`'s face (axis, side).
  tandem::NodeId first(tandem::NodeId node, int axis = -1, int side = 0) const;

  // The face of brother(a) that a touches: (the axis of the cut between them, 0 when brother(a)
  // is the high side, 1 when the low side). `a` must not be the root.
  static std::array<int, 2> face_towards(const tandem::BlockTree& tree, tandem::NodeId a);

private:
  static constexpr std::size_t kTotal = 6;
  static std::size_t index(tandem::NodeId n) { return static_cast<std::size_t>(n); }
  std::uint32_t count(tandem::NodeId node, int axis, int side) const {
    return axis < 0 ? total(node) : on_face(node, axis, side);
  }

  const tandem::BlockTree& tree_;
  std::vector<std::array<std::uint32_t, 7>> counts_;
};

} // namespace geotandem::runtime::detail
