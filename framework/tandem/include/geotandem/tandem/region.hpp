#pragma once
// The part of the cube a working surface covers (ALGORITHM.md, "Extended time lag"): a union of
// blocks of cells. After merges it need not be a box (a node merged with a nephew is L-shaped).
// Its *open faces* are the parts of its boundary that are not on the faces of the whole cube: a
// neighbour will arrive there later, so the surface must stay unsimplified near them.
//
// Units: index coordinates of the whole cube (voxel units). A block of cells [lo, hi) spans the
// coordinates [lo, hi] on each axis (cell i lies between samples i and i + 1); the whole cube of
// n samples is the cells [0, n - 1) (marching_cubes.hpp, cube_cells()).

#include <array>
#include <string>
#include <vector>

#include "geotandem/volume/box.hpp"

namespace geotandem::tandem {

// An axis-aligned rectangle of the plane x[axis] = plane: the other two axes, in increasing
// order, span [lo[0], hi[0]] x [lo[1], hi[1]].
struct OpenFace {
  int axis = 0;
  double plane = 0.0;
  std::array<double, 2> lo{0.0, 0.0};
  std::array<double, 2> hi{0.0, 0.0};

  // Euclidean distance from p to the rectangle, and its square.
  double distance(const std::array<double, 3>& p) const;
  double distance_squared(const std::array<double, 3>& p) const;
  bool operator==(const OpenFace&) const = default;
};

class Region {
public:
  // An empty region (no blocks, no open faces).
  Region() = default;
  // `cube_cells`: the cells of the whole cube; `blocks`: disjoint non-empty boxes of cells inside
  // it. Throws InvalidArgument naming the offending box when a block is empty, leaves the cube or
  // overlaps another.
  Region(const volume::Box& cube_cells, std::vector<volume::Box> blocks);
  // One block of the cube.
  static Region block(const volume::Box& cube_cells, const volume::Box& block_cells) {
    return Region(cube_cells, {block_cells});
  }

  const volume::Box& cube() const { return cube_; }
  const std::vector<volume::Box>& blocks() const { return blocks_; }
  // Sorted by axis, then plane.
  const std::vector<OpenFace>& open_faces() const { return open_faces_; }
  bool empty() const { return blocks_.empty(); }

  // The open face nearest p: its index in open_faces() (-1 when there is none), its distance
  // (+infinity when there is none) and the point of it nearest p (the face's two in-plane
  // coordinates, in the order of OpenFace::lo).
  struct NearestFace {
    int index = -1;
    double distance = 0.0;
    std::array<double, 2> at{0.0, 0.0};
  };
  NearestFace nearest_open_face(const std::array<double, 3>& p) const;
  // Distance from p to the nearest open face; +infinity when there is none.
  double distance_to_open_faces(const std::array<double, 3>& p) const { return nearest_open_face(p).distance; }
  // Whether the ball (centre, radius) stays clear of every open face: distance > radius.
  bool ball_clear(const std::array<double, 3>& centre, double radius) const {
    return distance_to_open_faces(centre) > radius;
  }
  // Whether p lies on an open face (within `tolerance`).
  bool on_open_face(const std::array<double, 3>& p, double tolerance = 1e-9) const {
    return distance_to_open_faces(p) <= tolerance;
  }
  // Whether p lies in the region (closed boxes).
  bool contains(const std::array<double, 3>& p) const;
  // The smallest box of cells holding every block (an empty box for an empty region).
  volume::Box bounds() const;

  // The union with a region of the same cube; when the union fills its bounding box (brothers),
  // it is that box as a single block. Throws InvalidArgument when the cubes differ or the blocks
  // overlap. The open faces are the same, in the same order, as Region(cube, blocks) would find,
  // but only the planes where `other` has block faces are computed again: O(this + other), not
  // O(this^2), for a worker's region that takes in one leaf at a time.
  Region merged_with(const Region& other) const;

  // For each open face of this region, the index of an open face of `later` that holds the whole
  // of it (same plane, its rectangle inside), or -1 when none does: the face was closed, in part
  // or whole, or the later region cut it differently. A point of a face that maps to an index is
  // still on an open face of `later`.
  std::vector<int> open_faces_kept_in(const Region& later) const;
  // The index of an open face that holds the whole of `piece` (the same plane, its rectangle
  // inside), or -1 when none does.
  int open_face_holding(const OpenFace& piece) const;

  // "cube [..] blocks {[..], [..]} open faces N", for messages.
  std::string to_string() const;

private:
  volume::Box cube_{};
  std::vector<volume::Box> blocks_;
  std::vector<OpenFace> open_faces_;
};

} // namespace geotandem::tandem
