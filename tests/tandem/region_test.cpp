// Regions and their open faces (region.hpp): the part of the cube a working surface covers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/tandem/region.hpp"

namespace geotandem::tandem {
namespace {

using volume::Box;

TEST(Region, InteriorBlockHasSixOpenFacesCornerBlockThree) {
  const Box cube{{0, 0, 0}, {30, 30, 30}};
  const Region inner = Region::block(cube, Box{{10, 10, 10}, {20, 20, 20}});
  EXPECT_EQ(inner.open_faces().size(), 6u);
  // Centre of the block: 5 voxels from every face.
  EXPECT_DOUBLE_EQ(inner.distance_to_open_faces({15, 15, 15}), 5.0);
  EXPECT_DOUBLE_EQ(inner.distance_to_open_faces({11, 15, 15}), 1.0);
  EXPECT_TRUE(inner.on_open_face({10, 12, 13}));
  EXPECT_TRUE(inner.ball_clear({15, 15, 15}, 4.9));
  EXPECT_FALSE(inner.ball_clear({15, 15, 15}, 5.0));

  const Region corner = Region::block(cube, Box{{0, 0, 0}, {10, 10, 10}});
  EXPECT_EQ(corner.open_faces().size(), 3u);
  // Near the cube's own faces nothing is open: only the faces at 10 count.
  EXPECT_DOUBLE_EQ(corner.distance_to_open_faces({0, 0, 0}), 10.0);
  EXPECT_DOUBLE_EQ(corner.distance_to_open_faces({1, 2, 7}), 3.0);

  const Region whole = Region::block(cube, cube);
  EXPECT_TRUE(whole.open_faces().empty());
  EXPECT_EQ(whole.distance_to_open_faces({15, 15, 15}), std::numeric_limits<double>::infinity());
}

TEST(Region, MergedBrothersLoseTheirCommonFace) {
  const Box cube{{0, 0, 0}, {40, 20, 20}};
  const Region left = Region::block(cube, Box{{0, 0, 0}, {20, 20, 20}});
  const Region right = Region::block(cube, Box{{20, 0, 0}, {40, 20, 20}});
  EXPECT_EQ(left.open_faces().size(), 1u);
  EXPECT_TRUE(left.on_open_face({20, 5, 5}));
  const Region both = left.merged_with(right);
  EXPECT_TRUE(both.open_faces().empty());
  EXPECT_FALSE(both.on_open_face({20, 5, 5}));
  EXPECT_THROW(left.merged_with(left), InvalidArgument);
}

// A worker's region after many extractions: a staircase of leaves. Its open faces are joined
// into few rectangles, and its distances equal the distance to the open boundary cut into unit
// squares (an oracle that knows nothing of rectangles).
TEST(Region, ManyLeavesJoinTheirOpenFacesAndKeepEveryDistance) {
  const Box cube{{0, 0, 0}, {24, 24, 12}};
  std::vector<Box> leaves;
  for (std::int64_t i = 0; i < 6; ++i)
    for (std::int64_t j = 0; j < 6; ++j)
      for (std::int64_t k = 0; k < 3; ++k)
        if (i + j + k < 7 && (i + 2 * j) % 5 != 3)
          leaves.push_back(Box{{4 * i, 4 * j, 4 * k}, {4 * i + 4, 4 * j + 4, 4 * k + 4}});
  const Region region(cube, leaves);
  // Unit squares of every leaf face that is neither on the cube's boundary nor covered by a leaf.
  auto inside = [&](double x, double y, double z) {
    for (const Box& b : leaves)
      if (x > b.lo[0] && x < b.hi[0] && y > b.lo[1] && y < b.hi[1] && z > b.lo[2] && z < b.hi[2]) return true;
    return false;
  };
  std::vector<OpenFace> squares;
  for (const Box& b : leaves)
    for (int axis = 0; axis < 3; ++axis) {
      const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
      for (int side = 0; side < 2; ++side) {
        const std::int64_t plane = side == 0 ? b.lo[axis] : b.hi[axis];
        if (plane == cube.lo[axis] || plane == cube.hi[axis]) continue;
        for (std::int64_t a = b.lo[u]; a < b.hi[u]; ++a)
          for (std::int64_t c = b.lo[v]; c < b.hi[v]; ++c) {
            std::array<double, 3> beyond{};
            beyond[static_cast<std::size_t>(axis)] = static_cast<double>(plane) + (side == 0 ? -0.5 : 0.5);
            beyond[static_cast<std::size_t>(u)] = static_cast<double>(a) + 0.5;
            beyond[static_cast<std::size_t>(v)] = static_cast<double>(c) + 0.5;
            if (inside(beyond[0], beyond[1], beyond[2])) continue;
            squares.push_back(OpenFace{axis, static_cast<double>(plane), {double(a), double(c)}, {a + 1.0, c + 1.0}});
          }
      }
    }
  ASSERT_GT(squares.size(), 100u);
  EXPECT_LT(region.open_faces().size() * 4, squares.size()) << "open faces are joined";
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-2.0, 26.0);
  for (int n = 0; n < 2000; ++n) {
    const std::array<double, 3> p{coordinate(random), coordinate(random), coordinate(random) / 2.0};
    double oracle = std::numeric_limits<double>::infinity();
    for (const OpenFace& f : squares)
      oracle = std::min(oracle, f.distance(p));
    EXPECT_EQ(region.distance_to_open_faces(p), oracle) << p[0] << " " << p[1] << " " << p[2];
  }
}

TEST(Region, LShapedRegionKeepsOnlyTheUncoveredPartOfAFace) {
  // Three quarters of a 2 x 2 x 1 arrangement of blocks in a cube of 40 x 40 x 20 cells.
  const Box cube{{0, 0, 0}, {40, 40, 20}};
  const Region l(cube, {Box{{0, 0, 0}, {20, 20, 20}}, Box{{20, 0, 0}, {40, 20, 20}}, Box{{0, 20, 0}, {20, 40, 20}}});
  // The missing quarter [20,40] x [20,40] is bounded by two open faces: x = 20 for y in [20, 40]
  // and y = 20 for x in [20, 40].
  ASSERT_EQ(l.open_faces().size(), 2u);
  EXPECT_TRUE(l.on_open_face({20, 30, 10}));
  EXPECT_TRUE(l.on_open_face({30, 20, 10}));
  EXPECT_FALSE(l.on_open_face({20, 10, 10})); // the face between the first two blocks is interior
  EXPECT_FALSE(l.on_open_face({10, 20, 10}));
  // From the inner corner region, the nearest open face is the concave corner's edge.
  EXPECT_NEAR(l.distance_to_open_faces({17, 17, 10}), std::sqrt(18.0), 1e-12);
  EXPECT_DOUBLE_EQ(l.distance_to_open_faces({5, 5, 10}), std::sqrt(15.0 * 15.0 * 2.0));
  EXPECT_TRUE(l.contains({5, 35, 3}));
  EXPECT_FALSE(l.contains({35, 35, 3}));
}

TEST(Region, TheNearestOpenFaceIsNamed) {
  const Box cube{{0, 0, 0}, {40, 40, 20}};
  const Region l(cube, {Box{{0, 0, 0}, {20, 20, 20}}, Box{{20, 0, 0}, {40, 20, 20}}, Box{{0, 20, 0}, {20, 40, 20}}});
  std::mt19937 random(5);
  std::uniform_real_distribution<double> coordinate(-1.0, 41.0);
  for (int n = 0; n < 500; ++n) {
    const std::array<double, 3> p{coordinate(random), coordinate(random), coordinate(random) / 2.0};
    const Region::NearestFace nearest = l.nearest_open_face(p);
    ASSERT_GE(nearest.index, 0);
    ASSERT_LT(static_cast<std::size_t>(nearest.index), l.open_faces().size());
    EXPECT_EQ(nearest.distance, l.open_faces()[static_cast<std::size_t>(nearest.index)].distance(p));
    EXPECT_EQ(nearest.distance, l.distance_to_open_faces(p));
    // The point it names lies on that face, at that distance from p.
    const OpenFace& face = l.open_faces()[static_cast<std::size_t>(nearest.index)];
    const std::size_t axis = static_cast<std::size_t>(face.axis), u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
    std::array<double, 3> q{};
    q[axis] = face.plane;
    q[u] = nearest.at[0];
    q[v] = nearest.at[1];
    EXPECT_EQ(face.distance(q), 0.0);
    EXPECT_NEAR(std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]), nearest.distance, 1e-9);
  }
  const Region whole = Region::block(cube, cube);
  EXPECT_EQ(whole.nearest_open_face({1, 2, 3}).index, -1);
}

// A merge keeps the parked edges whose face stays open (open_faces_kept_in). Oracle: a face of
// the earlier region is kept when every unit square of it is still open in the later region (the
// cell beyond it is not in the later region) and one later face holds all of them; its index must
// then name such a face, and no other face may be kept.
TEST(Region, AFaceIsKeptExactlyWhenALaterOpenFaceHoldsAllOfIt) {
  const Box cube{{0, 0, 0}, {24, 24, 12}};
  std::size_t kept_count = 0, closed_count = 0;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    std::mt19937 random(seed);
    std::vector<Box> earlier, later;
    for (std::int64_t i = 0; i < 6; ++i)
      for (std::int64_t j = 0; j < 6; ++j)
        for (std::int64_t k = 0; k < 3; ++k) {
          const Box leaf{{4 * i, 4 * j, 4 * k}, {4 * i + 4, 4 * j + 4, 4 * k + 4}};
          const unsigned draw = random() % 10;
          if (draw < 4) earlier.push_back(leaf);
          if (draw < 6) later.push_back(leaf);
        }
    const Region before(cube, earlier), after(cube, later);
    for (const Region* r : {&before, &after}) // sorted by axis, then plane (open_face_holding searches)
      ASSERT_TRUE(
          std::is_sorted(r->open_faces().begin(), r->open_faces().end(), [](const OpenFace& x, const OpenFace& y) {
            return std::pair(x.axis, x.plane) < std::pair(y.axis, y.plane);
          }));
    const std::vector<int> kept = before.open_faces_kept_in(after);
    ASSERT_EQ(kept.size(), before.open_faces().size());
    for (std::size_t f = 0; f < kept.size(); ++f) {
      const OpenFace& face = before.open_faces()[f];
      const auto axis = static_cast<std::size_t>(face.axis);
      const std::size_t u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
      std::vector<std::array<double, 3>> centres; // of its unit squares
      bool still_open = true;
      for (double a = face.lo[0]; a < face.hi[0]; a += 1.0)
        for (double c = face.lo[1]; c < face.hi[1]; c += 1.0) {
          std::array<double, 3> p{};
          p[axis] = face.plane;
          p[u] = a + 0.5;
          p[v] = c + 0.5;
          centres.push_back(p);
          std::array<double, 3> below = p, above = p;
          below[axis] -= 0.5;
          above[axis] += 0.5;
          if (after.contains(below) && after.contains(above)) still_open = false;
        }
      const auto holds_all = [&](const OpenFace& g) {
        if (g.axis != face.axis || g.plane != face.plane) return false;
        for (const auto& p : centres)
          if (p[u] < g.lo[0] || p[u] > g.hi[0] || p[v] < g.lo[1] || p[v] > g.hi[1]) return false;
        return true;
      };
      const bool oracle = still_open && std::any_of(after.open_faces().begin(), after.open_faces().end(), holds_all);
      ASSERT_EQ(kept[f] >= 0, oracle) << "seed " << seed << " face " << f;
      // Each unit square of the face: held by a later face exactly when it is still open there.
      for (const auto& p : centres) {
        OpenFace square = face;
        square.lo = {p[u] - 0.5, p[v] - 0.5};
        square.hi = {p[u] + 0.5, p[v] + 0.5};
        std::array<double, 3> below = p, above = p;
        below[axis] -= 0.5;
        above[axis] += 0.5;
        const int holder = after.open_face_holding(square);
        ASSERT_EQ(holder >= 0, !(after.contains(below) && after.contains(above)));
        if (holder >= 0) {
          EXPECT_TRUE(after.open_faces()[static_cast<std::size_t>(holder)].distance(p) == 0.0);
        }
      }
      if (kept[f] >= 0) {
        ASSERT_LT(static_cast<std::size_t>(kept[f]), after.open_faces().size());
        EXPECT_TRUE(holds_all(after.open_faces()[static_cast<std::size_t>(kept[f])]));
        ++kept_count;
      } else if (!still_open) {
        ++closed_count;
      }
    }
  }
  EXPECT_GT(kept_count, 50u);
  EXPECT_GT(closed_count, 50u);
}

// A worker's region grows one leaf (or one other worker's region) at a time, and merged_with()
// computes again only the planes the newcomer has faces on. Oracle: the region built at once from
// the same blocks in the same order. The open faces must be the same rectangles in the same order
// (the parked edges name a face by its index), at every step.
TEST(Region, GrowingOneLeafAtATimeGivesTheFacesOfAWholeComputation) {
  const Box cube{{0, 0, 0}, {32, 24, 16}};
  std::size_t steps = 0, multi = 0;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937 random(seed);
    std::vector<Box> leaves;
    for (std::int64_t i = 0; i < 8; ++i)
      for (std::int64_t j = 0; j < 6; ++j)
        for (std::int64_t k = 0; k < 4; ++k)
          leaves.push_back(Box{{4 * i, 4 * j, 4 * k}, {4 * i + 4, 4 * j + 4, 4 * k + 4}});
    std::shuffle(leaves.begin(), leaves.end(), random);
    // Two growing regions that sometimes merge with each other, as two workers' surfaces do.
    std::array<Region, 2> region;
    for (std::size_t n = 0; n < leaves.size(); ++n) {
      Region& r = region[random() % 2];
      r = r.merged_with(Region::block(cube, leaves[n]));
      const Region whole(cube, r.blocks());
      ASSERT_EQ(r.open_faces(), whole.open_faces()) << "seed " << seed << " leaf " << n;
      ++steps;
      if (random() % 17 == 0 && !region[0].empty() && !region[1].empty()) {
        region[0] = region[0].merged_with(region[1]);
        region[1] = Region();
        const Region again(cube, region[0].blocks());
        ASSERT_EQ(region[0].open_faces(), again.open_faces()) << "seed " << seed << " after leaf " << n;
        ++multi;
      }
    }
    const Region all = region[0].merged_with(region[1]);
    ASSERT_EQ(all.blocks().size(), 1u) << "the whole cube is one block";
    EXPECT_TRUE(all.open_faces().empty());
  }
  EXPECT_GT(multi, 5u);
  EXPECT_EQ(steps, 6u * 192u);
}

// The overlap test sweeps along the first axis; oracle: every pair compared.
TEST(Region, FindsAnOverlapAmongManyBlocksExactlyWhenThereIsOne) {
  const Box cube{{0, 0, 0}, {48, 40, 40}};
  std::size_t refused = 0;
  for (unsigned seed = 1; seed <= 300; ++seed) {
    std::mt19937 random(seed);
    std::vector<Box> blocks;
    for (int n = 0; n < 12; ++n) {
      Box b;
      for (int a = 0; a < 3; ++a) {
        b.lo[a] = random() % 36;
        b.hi[a] = b.lo[a] + 1 + random() % (a == 0 ? 12 : 4);
      }
      blocks.push_back(b);
    }
    bool any = false;
    for (std::size_t i = 0; i < blocks.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        any = any || !blocks[i].intersection(blocks[j]).empty();
    if (any) {
      EXPECT_THROW(Region(cube, blocks), InvalidArgument) << "seed " << seed;
      ++refused;
    } else {
      EXPECT_NO_THROW(Region(cube, blocks)) << "seed " << seed;
    }
    // The same, one block at a time through merged_with().
    Region grown;
    bool threw = false;
    for (const Box& b : blocks) {
      try {
        grown = grown.merged_with(Region::block(cube, b));
      } catch (const InvalidArgument&) {
        threw = true;
        break;
      }
    }
    EXPECT_EQ(threw, any) << "seed " << seed;
  }
  EXPECT_GT(refused, 50u);
  EXPECT_LT(refused, 250u);
}

TEST(Region, RejectsBlocksOutsideTheCubeOrOverlapping) {
  const Box cube{{0, 0, 0}, {10, 10, 10}};
  EXPECT_THROW(Region::block(cube, Box{{0, 0, 0}, {11, 5, 5}}), InvalidArgument);
  EXPECT_THROW(Region::block(cube, Box{{3, 3, 3}, {3, 5, 5}}), InvalidArgument);
  EXPECT_THROW(Region(cube, {Box{{0, 0, 0}, {6, 10, 10}}, Box{{5, 0, 0}, {10, 10, 10}}}), InvalidArgument);
}

} // namespace
} // namespace geotandem::tandem
