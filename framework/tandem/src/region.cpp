#include "geotandem/tandem/region.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>
#include <utility>

#include "geotandem/core/error.hpp"

namespace geotandem::tandem {
namespace {

struct Rect {
  double lo0, hi0, lo1, hi1;
  bool has_area() const { return hi0 > lo0 && hi1 > lo1; }
};

// R minus C, as up to four rectangles with positive area.
void subtract(const Rect& r, const Rect& c, std::vector<Rect>& out) {
  const double lo0 = std::max(r.lo0, c.lo0), hi0 = std::min(r.hi0, c.hi0);
  const double lo1 = std::max(r.lo1, c.lo1), hi1 = std::min(r.hi1, c.hi1);
  if (!(hi0 > lo0 && hi1 > lo1)) {
    out.push_back(r);
    return;
  }
  const Rect pieces[4] = {
      {r.lo0, lo0, r.lo1, r.hi1}, // before c along the first axis
      {hi0, r.hi0, r.lo1, r.hi1}, // after c along the first axis
      {lo0, hi0, r.lo1, lo1},     // inside c's span, before it along the second axis
      {lo0, hi0, hi1, r.hi1},     // inside c's span, after it along the second axis
  };
  for (const Rect& p : pieces)
    if (p.has_area()) out.push_back(p);
}

void other_axes(int axis, int& u, int& v) {
  u = axis == 0 ? 1 : 0;
  v = axis == 2 ? 1 : 2;
}

} // namespace

double OpenFace::distance_squared(const std::array<double, 3>& p) const {
  int u = 0, v = 0;
  other_axes(axis, u, v);
  const double dn = p[static_cast<std::size_t>(axis)] - plane;
  const double pu = p[static_cast<std::size_t>(u)], pv = p[static_cast<std::size_t>(v)];
  const double du = pu < lo[0] ? lo[0] - pu : (pu > hi[0] ? pu - hi[0] : 0.0);
  const double dv = pv < lo[1] ? lo[1] - pv : (pv > hi[1] ? pv - hi[1] : 0.0);
  return dn * dn + du * du + dv * dv;
}

double OpenFace::distance(const std::array<double, 3>& p) const {
  return std::sqrt(distance_squared(p));
}

namespace {

InvalidArgument overlapping(const volume::Box& a, const volume::Box& b) {
  return InvalidArgument("region: blocks " + a.to_string() + " and " + b.to_string() + " overlap",
                         {.block = b.to_string()}, "merge only regions made of different blocks");
}

// A plane of the cube where blocks have faces: axis, coordinate.
using Plane = std::pair<int, std::int64_t>;

// The planes of the faces of `boxes`, sorted, each once.
std::vector<Plane> planes_of(const std::vector<volume::Box>& boxes) {
  std::vector<Plane> planes;
  planes.reserve(6 * boxes.size());
  for (const volume::Box& b : boxes)
    for (int axis = 0; axis < 3; ++axis) {
      planes.emplace_back(axis, b.lo[axis]);
      planes.emplace_back(axis, b.hi[axis]);
    }
  std::sort(planes.begin(), planes.end());
  planes.erase(std::unique(planes.begin(), planes.end()), planes.end());
  return planes;
}

// The blocks with a face on one plane: `low`, those whose low face lies on it (they lie above it);
// `high`, those whose high face does. Each in the order of the region's blocks.
struct PlaneBlocks {
  std::vector<std::size_t> low, high;
};

// A region of many leaves (a worker's surface after many extractions) has one open rectangle per
// leaf face; every placed edge asks its distance to them. Rectangles of one plane that share a
// whole edge are joined: the set of points, and so every distance, is exactly the same. Two rounds
// at most, the second only when the first joined some; the faces end sorted by their first axis's
// span, then their second axis's start (a whole key: rectangles of one plane do not overlap).
void coalesce_plane(std::vector<OpenFace>& faces) {
  auto join_along = [&faces](int along) {
    const int across = 1 - along;
    std::sort(faces.begin(), faces.end(), [across, along](const OpenFace& a, const OpenFace& b) {
      return std::tie(a.lo[across], a.hi[across], a.lo[along]) < std::tie(b.lo[across], b.hi[across], b.lo[along]);
    });
    std::vector<OpenFace> joined;
    joined.reserve(faces.size());
    for (const OpenFace& f : faces) {
      if (!joined.empty()) {
        OpenFace& last = joined.back();
        if (last.lo[across] == f.lo[across] && last.hi[across] == f.hi[across] && last.hi[along] == f.lo[along]) {
          last.hi[along] = f.hi[along];
          continue;
        }
      }
      joined.push_back(f);
    }
    faces.swap(joined);
  };
  for (int round = 0; round < 2; ++round) {
    const std::size_t before = faces.size();
    join_along(0);
    join_along(1);
    if (faces.size() == before) break;
  }
}

// The open faces on one plane, sorted as coalesce_plane() leaves them: each block face there (not
// on the cube's own faces) minus the faces of the blocks facing it, then joined.
void add_open_faces_of_plane(const volume::Box& cube, const std::vector<volume::Box>& blocks, Plane plane,
                             const PlaneBlocks& on, std::vector<OpenFace>& out) {
  const auto [axis, at] = plane;
  int u = 0, v = 0;
  other_axes(axis, u, v);
  const auto rect = [&blocks, u, v](std::size_t n) {
    const volume::Box& b = blocks[n];
    return Rect{static_cast<double>(b.lo[u]), static_cast<double>(b.hi[u]), static_cast<double>(b.lo[v]),
                static_cast<double>(b.hi[v])};
  };
  std::vector<OpenFace> faces;
  std::vector<Rect> pieces, next;
  std::vector<std::pair<double, std::size_t>> facing; // (start along u, block), by start
  std::vector<std::pair<std::size_t, Rect>> covers;   // by block
  for (int side = 0; side < 2; ++side) {
    // A face of the whole cube is never open.
    if (at == (side == 0 ? cube.lo[axis] : cube.hi[axis])) continue;
    // The blocks on the other side, found by their span along u: a plane of a worker's region
    // can hold hundreds of leaf faces on each side.
    facing.clear();
    double widest = 0.0;
    for (std::size_t n : side == 0 ? on.high : on.low) {
      const Rect c = rect(n);
      facing.emplace_back(c.lo0, n);
      widest = std::max(widest, c.hi0 - c.lo0);
    }
    std::sort(facing.begin(), facing.end());
    for (std::size_t i : side == 0 ? on.low : on.high) {
      const Rect face = rect(i);
      // Parts covered by a block of the region on the other side are interior, not open. Those
      // that overlap the face are subtracted in the order of the blocks (the pieces depend on it).
      covers.clear();
      for (auto c = std::lower_bound(facing.begin(), facing.end(), std::pair(face.lo0 - widest, std::size_t{0}));
           c != facing.end() && c->first < face.hi0; ++c) {
        const Rect r = rect(c->second);
        if (r.hi0 > face.lo0 && r.lo1 < face.hi1 && r.hi1 > face.lo1) covers.emplace_back(c->second, r);
      }
      std::sort(covers.begin(), covers.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      pieces.assign(1, face);
      for (const auto& [n, cover] : covers) {
        next.clear();
        for (const Rect& r : pieces)
          subtract(r, cover, next);
        pieces.swap(next);
      }
      for (const Rect& r : pieces)
        faces.push_back(OpenFace{axis, static_cast<double>(at), {r.lo0, r.lo1}, {r.hi0, r.hi1}});
    }
  }
  coalesce_plane(faces);
  out.insert(out.end(), faces.begin(), faces.end());
}

// The open faces of the region `blocks` when only `planes` (sorted, each once) may differ from
// `before`: the faces of `before` on other planes are kept, those of `planes` computed from the
// blocks; in plane order. With every plane of the blocks and nothing before, a whole computation.
std::vector<OpenFace> open_faces_on(const volume::Box& cube, const std::vector<volume::Box>& blocks,
                                    const std::vector<Plane>& planes, const std::vector<OpenFace>& before) {
  // Only blocks with a face on a plane can cover a face of another block there.
  std::vector<PlaneBlocks> on(planes.size());
  const auto add = [&planes, &on](Plane plane, std::vector<std::size_t> PlaneBlocks::*side, std::size_t n) {
    const auto p = std::lower_bound(planes.begin(), planes.end(), plane);
    if (p != planes.end() && *p == plane) (on[static_cast<std::size_t>(p - planes.begin())].*side).push_back(n);
  };
  for (std::size_t n = 0; n < blocks.size(); ++n)
    for (int axis = 0; axis < 3; ++axis) {
      add({axis, blocks[n].lo[axis]}, &PlaneBlocks::low, n);
      add({axis, blocks[n].hi[axis]}, &PlaneBlocks::high, n);
    }
  std::vector<OpenFace> faces;
  faces.reserve(before.size() + 4 * planes.size());
  const auto plane_of = [](const OpenFace& f) { return Plane{f.axis, static_cast<std::int64_t>(f.plane)}; };
  auto kept = before.begin();
  for (std::size_t c = 0; c < planes.size(); ++c) {
    for (; kept != before.end() && plane_of(*kept) < planes[c]; ++kept)
      faces.push_back(*kept);
    while (kept != before.end() && plane_of(*kept) == planes[c])
      ++kept;
    add_open_faces_of_plane(cube, blocks, planes[c], on[c], faces);
  }
  faces.insert(faces.end(), kept, before.end());
  return faces;
}

} // namespace

Region::Region(const volume::Box& cube_cells, std::vector<volume::Box> blocks)
    : cube_(cube_cells), blocks_(std::move(blocks)) {
  if (cube_.empty())
    throw InvalidArgument("region: the cube's cells " + cube_.to_string() + " are empty", {},
                          "a cube needs at least two samples along every axis");
  for (const volume::Box& b : blocks_)
    if (b.empty() || !cube_.contains(b))
      throw InvalidArgument("region: block " + b.to_string() + " is empty or leaves the cube's cells " +
                                cube_.to_string(),
                            {.block = b.to_string()}, "blocks are boxes of cells inside the cube");
  // Overlaps, swept along the first axis: a block is compared only with the blocks that start
  // before it ends there (a region read from a worker's surface may hold thousands of leaves).
  std::vector<std::size_t> order(blocks_.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [this](std::size_t a, std::size_t b) {
    return std::pair(blocks_[a].lo[0], a) < std::pair(blocks_[b].lo[0], b);
  });
  for (std::size_t i = 0; i < order.size(); ++i)
    for (std::size_t j = i + 1; j < order.size() && blocks_[order[j]].lo[0] < blocks_[order[i]].hi[0]; ++j)
      if (blocks_[order[i]].overlaps(blocks_[order[j]]))
        throw overlapping(blocks_[std::min(order[i], order[j])], blocks_[std::max(order[i], order[j])]);
  open_faces_ = open_faces_on(cube_, blocks_, planes_of(blocks_), {});
}

Region::NearestFace Region::nearest_open_face(const std::array<double, 3>& p) const {
  // Squared distances, and a face whose plane alone is farther than the best so far is skipped;
  // the square root of the least is the least of the square roots.
  double best = std::numeric_limits<double>::infinity();
  int index = -1;
  for (std::size_t i = 0; i < open_faces_.size(); ++i) {
    const OpenFace& f = open_faces_[i];
    const double dn = p[static_cast<std::size_t>(f.axis)] - f.plane;
    if (dn * dn >= best) continue;
    const double d2 = f.distance_squared(p);
    if (d2 < best) {
      best = d2;
      index = static_cast<int>(i);
    }
  }
  NearestFace nearest{index, std::sqrt(best), {0.0, 0.0}};
  if (index >= 0) {
    const OpenFace& f = open_faces_[static_cast<std::size_t>(index)];
    int u = 0, v = 0;
    other_axes(f.axis, u, v);
    nearest.at = {std::clamp(p[static_cast<std::size_t>(u)], f.lo[0], f.hi[0]),
                  std::clamp(p[static_cast<std::size_t>(v)], f.lo[1], f.hi[1])};
  }
  return nearest;
}

std::vector<int> Region::open_faces_kept_in(const Region& later) const {
  std::vector<int> kept(open_faces_.size(), -1);
  for (std::size_t i = 0; i < open_faces_.size(); ++i)
    kept[i] = later.open_face_holding(open_faces_[i]);
  return kept;
}

int Region::open_face_holding(const OpenFace& piece) const {
  // The faces are sorted by axis and plane (open_faces_on() goes plane by plane).
  const auto plane = [](const OpenFace& f) { return std::pair<int, double>(f.axis, f.plane); };
  auto f = std::lower_bound(open_faces_.begin(), open_faces_.end(), plane(piece),
                            [&](const OpenFace& x, const std::pair<int, double>& key) { return plane(x) < key; });
  for (; f != open_faces_.end() && plane(*f) == plane(piece); ++f)
    if (f->lo[0] <= piece.lo[0] && f->lo[1] <= piece.lo[1] && piece.hi[0] <= f->hi[0] && piece.hi[1] <= f->hi[1])
      return static_cast<int>(f - open_faces_.begin());
  return -1;
}

bool Region::contains(const std::array<double, 3>& p) const {
  for (const volume::Box& b : blocks_) {
    bool inside = true;
    for (int a = 0; a < 3 && inside; ++a)
      inside = p[static_cast<std::size_t>(a)] >= static_cast<double>(b.lo[a]) &&
               p[static_cast<std::size_t>(a)] <= static_cast<double>(b.hi[a]);
    if (inside) return true;
  }
  return false;
}

volume::Box Region::bounds() const {
  if (blocks_.empty()) return {};
  volume::Box box = blocks_.front();
  for (const volume::Box& b : blocks_)
    box = box.hull(b);
  return box;
}

Region Region::merged_with(const Region& other) const {
  if (empty()) return other;
  if (other.empty()) return *this;
  if (!(cube_ == other.cube_))
    throw InvalidArgument("region: cannot merge regions of different cubes " + cube_.to_string() + " and " +
                          other.cube_.to_string());
  // Each side's blocks are disjoint already: only pairs across the two are compared.
  const volume::Box there = other.bounds();
  for (const volume::Box& a : blocks_)
    if (a.overlaps(there))
      for (const volume::Box& b : other.blocks_)
        if (a.overlaps(b)) throw overlapping(a, b);
  // A union that fills its bounding box (two brothers) is that box: one block, whose open faces
  // are whole rectangles, instead of one rectangle per face of every merged leaf (the distance to
  // the open faces is computed for every placed edge).
  const volume::Box bounds = this->bounds().hull(there);
  std::size_t cells = 0;
  for (const Region* r : {this, &other})
    for (const volume::Box& b : r->blocks_)
      cells += b.count();
  if (cells == bounds.count()) return Region(cube_, {bounds});

  // Only the planes where the other side's blocks have faces can change: their open faces are
  // computed again (exactly as a whole computation would, the blocks in the same order), the
  // others' kept. A worker's surface merges one leaf at a time into a region of thousands.
  Region merged;
  merged.cube_ = cube_;
  merged.blocks_ = blocks_;
  merged.blocks_.insert(merged.blocks_.end(), other.blocks_.begin(), other.blocks_.end());
  merged.open_faces_ = open_faces_on(cube_, merged.blocks_, planes_of(other.blocks_), open_faces_);
  return merged;
}

std::string Region::to_string() const {
  std::string s = "cube " + cube_.to_string() + " blocks {";
  for (std::size_t i = 0; i < blocks_.size(); ++i)
    s += (i ? ", " : "") + blocks_[i].to_string();
  return s + "} open faces " + std::to_string(open_faces_.size());
}

} // namespace geotandem::tandem
