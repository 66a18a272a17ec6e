// Block tree: the split covers the cube exactly, types follow the cuts, and the restricted-adjacency
// test agrees with geometry; the seed's figure 8 worked example.

#include <gtest/gtest.h>

#include <set>

#include "geotandem/core/error.hpp"
#include "geotandem/tandem/block_tree.hpp"

namespace geotandem::tandem {
namespace {

using volume::Box;

struct Shape {
  Box cube;
  std::int64_t leaf;
};

// Cubes of several shapes and leaf sizes, uneven ones included (odd sizes, non-zero origin).
const std::vector<Shape>& shapes() {
  static const std::vector<Shape> s = {
      {{{0, 0, 0}, {8, 8, 8}}, 2},   {{{0, 0, 0}, {16, 8, 4}}, 4},   {{{0, 0, 0}, {13, 7, 9}}, 3},
      {{{0, 0, 0}, {5, 31, 6}}, 4},  {{{2, 3, 1}, {19, 12, 30}}, 5}, {{{0, 0, 0}, {9, 9, 9}}, 2},
      {{{0, 0, 0}, {40, 3, 17}}, 6}, {{{0, 0, 0}, {1, 1, 1}}, 1},    {{{0, 0, 0}, {6, 6, 6}}, 100},
  };
  return s;
}

TEST(BlockTree, LeavesTileTheCubeAndRespectTheLeafSize) {
  for (const Shape& s : shapes()) {
    const BlockTree tree(s.cube, s.leaf);
    std::size_t cells = 0;
    for (NodeId leaf : tree.leaves()) {
      const BlockNode& n = tree.node(leaf);
      EXPECT_TRUE(n.is_leaf());
      EXPECT_TRUE(s.cube.contains(n.cells));
      for (int a = 0; a < 3; ++a)
        EXPECT_LE(n.cells.size(a), s.leaf) << tree.describe(leaf);
      cells += n.cells.count();
    }
    EXPECT_EQ(cells, s.cube.count()); // with the containment and the disjointness below: a tiling
    for (std::size_t x = 0; x < tree.leaves().size(); ++x)
      for (std::size_t y = x + 1; y < tree.leaves().size(); ++y)
        EXPECT_TRUE(tree.node(tree.leaves()[x]).cells.intersection(tree.node(tree.leaves()[y]).cells).empty());
    EXPECT_EQ(tree.size(), 2 * tree.leaves().size() - 1);
    // Every leaf's cells are found by leaf_of.
    for (NodeId leaf : tree.leaves()) {
      EXPECT_EQ(tree.leaf_of(tree.node(leaf).cells.lo), leaf);
      const auto& hi = tree.node(leaf).cells.hi;
      EXPECT_EQ(tree.leaf_of({hi[0] - 1, hi[1] - 1, hi[2] - 1}), leaf);
    }
    EXPECT_EQ(tree.leaf_of(s.cube.hi), kNoNode);
  }
}

TEST(BlockTree, NodesFollowTheirParentsCut) {
  for (const Shape& s : shapes()) {
    const BlockTree tree(s.cube, s.leaf);
    EXPECT_EQ(tree.node(tree.root()).type, NodeType::root);
    EXPECT_EQ(tree.brother(tree.root()), kNoNode);
    for (const BlockNode& n : tree.nodes()) {
      if (n.is_leaf()) continue;
      const BlockNode& low = tree.node(n.children[0]);
      const BlockNode& high = tree.node(n.children[1]);
      const int a = n.split_axis;
      // Cut perpendicular to the longest axis, the lowest one on ties, in the middle.
      for (int b = 0; b < 3; ++b) {
        EXPECT_GE(n.cells.size(a), n.cells.size(b));
        if (b < a) {
          EXPECT_GT(n.cells.size(a), n.cells.size(b));
        }
      }
      EXPECT_GT(n.cells.size(a), s.leaf);
      EXPECT_EQ(low.cells.hi[a], n.cells.lo[a] + n.cells.size(a) / 2);
      EXPECT_EQ(low.cells.hi[a], high.cells.lo[a]);
      EXPECT_EQ(low.cells.count() + high.cells.count(), n.cells.count());
      EXPECT_EQ(cut_axis(low.type), a);
      EXPECT_EQ(high.type, opposite(low.type));
      EXPECT_TRUE(low.type == NodeType::left || low.type == NodeType::up || low.type == NodeType::front);
      EXPECT_EQ(low.parent, n.id);
      EXPECT_EQ(low.depth, n.depth + 1);
      EXPECT_EQ(tree.brother(low.id), high.id);
      EXPECT_EQ(tree.brother(high.id), low.id);
    }
  }
}

TEST(BlockTree, RestrictedAdjacencyAgreesWithGeometry) {
  std::size_t adjacent = 0, apart = 0;
  for (const Shape& s : shapes()) {
    const BlockTree tree(s.cube, s.leaf);
    for (const BlockNode& p1 : tree.nodes()) {
      if (p1.id == tree.root()) continue;
      const NodeId p2 = tree.brother(p1.id);
      EXPECT_TRUE(tree.restricted_adjacent(p1.id, p2));
      EXPECT_TRUE(boxes_share_face(p1.cells, tree.node(p2).cells));
      for (const BlockNode& n : tree.nodes()) {
        if (n.id == p2 || !tree.is_ancestor(p2, n.id)) continue;
        const bool geometric = boxes_share_face(p1.cells, n.cells);
        EXPECT_EQ(tree.restricted_adjacent(p1.id, n.id), geometric)
            << tree.describe(p1.id) << " and nephew " << tree.describe(n.id);
        ++(geometric ? adjacent : apart);
      }
    }
  }
  EXPECT_GT(adjacent, 100u); // the property was exercised both ways
  EXPECT_GT(apart, 100u);
}

TEST(BlockTree, RestrictedAdjacencyRefusesNodesOutsideTheBrothersSubtree) {
  const BlockTree tree({{0, 0, 0}, {8, 8, 8}}, 2);
  EXPECT_THROW((void)tree.restricted_adjacent(tree.root(), 1), InvalidArgument);
  const NodeId a = tree.node(tree.root()).children[0];
  const NodeId a_child = tree.node(a).children[0];
  EXPECT_THROW((void)tree.restricted_adjacent(a, a_child), InvalidArgument); // own subtree
  EXPECT_THROW((void)tree.node(static_cast<NodeId>(tree.size())), InvalidArgument);
  EXPECT_THROW(BlockTree(Box{{0, 0, 0}, {0, 4, 4}}, 2), InvalidArgument);
  EXPECT_THROW(BlockTree(Box{{0, 0, 0}, {4, 4, 4}}, 0), InvalidArgument);
}

TEST(BlockTree, OpenFacesAreTheFacesInsideTheCube) {
  for (const Shape& s : shapes()) {
    const BlockTree tree(s.cube, s.leaf);
    EXPECT_FALSE(tree.open_faces(tree.root()).any());
    for (const BlockNode& n : tree.nodes()) {
      const OpenFaces f = tree.open_faces(n.id);
      for (int a = 0; a < 3; ++a) {
        // A face is open exactly when some leaf lies right behind it.
        bool low_neighbour = false, high_neighbour = false;
        for (NodeId leaf : tree.leaves()) {
          const Box& b = tree.node(leaf).cells;
          if (!boxes_share_face(n.cells, b)) continue;
          low_neighbour |= b.hi[a] == n.cells.lo[a];
          high_neighbour |= b.lo[a] == n.cells.hi[a];
        }
        EXPECT_EQ(f.low[a], low_neighbour) << tree.describe(n.id) << " axis " << a;
        EXPECT_EQ(f.high[a], high_neighbour) << tree.describe(n.id) << " axis " << a;
      }
    }
  }
}

TEST(BlockTree, SeedFigure8Example) {
  // The seed's figure 8: leaves 1..8, their parents n9 (1, 2), n10 (3, 4), n11 (5, 6), n12 (7, 8),
  // then n13 (n9, n10) and n14 (n11, n12) under the root. The text gives type(n13) = left (its
  // opposite is right), type(leaf6) = down, type(n11) = down and type(n12) = right. The last two
  // cannot both hold: n11 and n12 are brothers, so they come from one cut and their types are
  // opposite. The conclusion about leaf7 rests on type(n12) = right, so n14 is cut along x (n11 =
  // left, n12 = right) and type(n11) = down is the text's slip; leaf6 = down means n11 is cut
  // along y. A cube of 4 x 2 x 1 leaves of 8 cells gives exactly that tree.
  const BlockTree tree({{0, 0, 0}, {32, 16, 8}}, 8);
  ASSERT_EQ(tree.leaves().size(), 8u);
  std::array<NodeId, 15> n{}; // n[1..8] the leaves, n[9..14] the inner nodes
  for (int i = 0; i < 8; ++i)
    n[static_cast<std::size_t>(i + 1)] = tree.leaves()[static_cast<std::size_t>(i)];
  for (int i = 0; i < 4; ++i) {
    const NodeId parent = tree.node(n[static_cast<std::size_t>(2 * i + 1)]).parent;
    EXPECT_EQ(parent, tree.node(n[static_cast<std::size_t>(2 * i + 2)]).parent);
    n[static_cast<std::size_t>(9 + i)] = parent;
  }
  n[13] = tree.node(n[9]).parent;
  n[14] = tree.node(n[11]).parent;
  EXPECT_EQ(tree.node(n[10]).parent, n[13]);
  EXPECT_EQ(tree.node(n[12]).parent, n[14]);
  EXPECT_EQ(tree.node(n[13]).parent, tree.root());
  EXPECT_EQ(tree.brother(n[13]), n[14]);

  // The types the text states (n11 corrected, see above).
  EXPECT_EQ(tree.node(n[13]).type, NodeType::left);
  EXPECT_EQ(opposite(tree.node(n[13]).type), NodeType::right);
  EXPECT_EQ(tree.node(n[6]).type, NodeType::down);
  EXPECT_EQ(tree.node(n[11]).type, NodeType::left);
  EXPECT_EQ(tree.node(n[12]).type, NodeType::right);

  // Brothers merge: leaves 1 and 2 (n9), 3 and 4 (n10), then n9 and n10 (n13).
  EXPECT_TRUE(tree.restricted_adjacent(n[1], n[2]));
  EXPECT_TRUE(tree.restricted_adjacent(n[3], n[4]));
  EXPECT_TRUE(tree.restricted_adjacent(n[9], n[10]));
  // The text's conclusions: leaf6 can merge with n13, leaf7 cannot.
  EXPECT_TRUE(tree.restricted_adjacent(n[13], n[6]));
  EXPECT_FALSE(tree.restricted_adjacent(n[13], n[7]));
  EXPECT_TRUE(boxes_share_face(tree.node(n[13]).cells, tree.node(n[6]).cells));
  EXPECT_FALSE(boxes_share_face(tree.node(n[13]).cells, tree.node(n[7]).cells));
  // And the rest of n14's subtree, for completeness: n11 and leaf5 touch n13, n12 and leaf8 do not.
  EXPECT_TRUE(tree.restricted_adjacent(n[13], n[11]));
  EXPECT_TRUE(tree.restricted_adjacent(n[13], n[5]));
  EXPECT_FALSE(tree.restricted_adjacent(n[13], n[12]));
  EXPECT_FALSE(tree.restricted_adjacent(n[13], n[8]));
}

TEST(BlockTree, BoxesShareFaceOnlyAlongAFace) {
  const Box a{{0, 0, 0}, {4, 4, 4}};
  EXPECT_TRUE(boxes_share_face(a, Box{{4, 1, 1}, {6, 3, 3}}));
  EXPECT_TRUE(boxes_share_face(Box{{4, 1, 1}, {6, 3, 3}}, a));
  EXPECT_FALSE(boxes_share_face(a, Box{{4, 4, 0}, {6, 6, 4}})); // along an edge only
  EXPECT_FALSE(boxes_share_face(a, Box{{4, 4, 4}, {6, 6, 6}})); // a corner
  EXPECT_FALSE(boxes_share_face(a, Box{{5, 0, 0}, {6, 4, 4}})); // a gap
  EXPECT_FALSE(boxes_share_face(a, Box{{3, 0, 0}, {6, 4, 4}})); // overlapping
}

} // namespace
} // namespace geotandem::tandem
