#include "geotandem/tandem/region.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>
#include <unordered_map>
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

Region::Region(const volume::Box& cube_cells, std::vector<volume::Box> blocks)
    : cube_(cube_cells), blocks_(std::move(blocks)) {
  if (cube_.empty())
    throw InvalidArgument("region: the cube's cells " + cube_.to_string() + " are empty", {},
                          "a cube needs at least two samples along every axis");
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    const volume::Box& b = blocks_[i];
    if (b.empty() || !cube_.contains(b))
      throw InvalidArgument("region: block " + b.to_string() + " is empty or leaves the cube's cells " +
                                cube_.to_string(),
                            {.block = b.to_string()}, "blocks are boxes of cells inside the cube");
    for (std::size_t j = 0; j < i; ++j)
      if (!b.intersection(blocks_[j]).empty())
        throw InvalidArgument("region: blocks " + blocks_[j].to_string() + " and " + b.to_string() + " overlap",
                              {.block = b.to_string()}, "merge only regions made of different blocks");
  }
  compute_open_faces();
}

void Region::compute_open_faces() {
  open_faces_.clear();
  // The boxes whose low (high) face lies on each plane of each axis, in the order of blocks_: only
  // those can cover a face of another box. A worker's region may hold thousands of leaves, and
  // looking at every other box for every face cost O(n^2).
  std::array<std::unordered_map<std::int64_t, std::vector<std::size_t>>, 3> low_faces, high_faces;
  for (std::size_t n = 0; n < blocks_.size(); ++n)
    for (std::size_t axis = 0; axis < 3; ++axis) {
      low_faces[axis][blocks_[n].lo[axis]].push_back(n);
      high_faces[axis][blocks_[n].hi[axis]].push_back(n);
    }
  std::vector<Rect> pieces, next;
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    const volume::Box& b = blocks_[i];
    for (int axis = 0; axis < 3; ++axis) {
      int u = 0, v = 0;
      other_axes(axis, u, v);
      for (int side = 0; side < 2; ++side) {
        const std::int64_t plane = side == 0 ? b.lo[axis] : b.hi[axis];
        const std::int64_t cube_plane = side == 0 ? cube_.lo[axis] : cube_.hi[axis];
        if (plane == cube_plane) continue; // a face of the whole cube: never open
        pieces.assign(1, Rect{static_cast<double>(b.lo[u]), static_cast<double>(b.hi[u]), static_cast<double>(b.lo[v]),
                              static_cast<double>(b.hi[v])});
        // Parts covered by a block of the region on the other side are interior, not open.
        const auto& facing = (side == 0 ? high_faces : low_faces)[static_cast<std::size_t>(axis)];
        const auto touching = facing.find(plane);
        if (touching != facing.end())
          for (std::size_t n : touching->second) {
            if (n == i) continue;
            const volume::Box& c = blocks_[n];
            const Rect cover{static_cast<double>(c.lo[u]), static_cast<double>(c.hi[u]), static_cast<double>(c.lo[v]),
                             static_cast<double>(c.hi[v])};
            next.clear();
            for (const Rect& r : pieces)
              subtract(r, cover, next);
            pieces.swap(next);
          }
        for (const Rect& r : pieces)
          open_faces_.push_back(OpenFace{axis, static_cast<double>(plane), {r.lo0, r.lo1}, {r.hi0, r.hi1}});
      }
    }
  }
  coalesce_open_faces();
}

// A region of many leaves (a worker's surface after many extractions) has one open rectangle per
// leaf face; every placed edge asks its distance to them. Rectangles of one plane that share a
// whole edge are joined: the set of points, and so every distance, is exactly the same.
void Region::coalesce_open_faces() {
  auto join_along = [this](int along) {
    const int across = 1 - along;
    std::sort(open_faces_.begin(), open_faces_.end(), [across, along](const OpenFace& a, const OpenFace& b) {
      return std::tie(a.axis, a.plane, a.lo[across], a.hi[across], a.lo[along]) <
             std::tie(b.axis, b.plane, b.lo[across], b.hi[across], b.lo[along]);
    });
    std::vector<OpenFace> joined;
    joined.reserve(open_faces_.size());
    for (const OpenFace& f : open_faces_) {
      if (!joined.empty()) {
        OpenFace& last = joined.back();
        if (last.axis == f.axis && last.plane == f.plane && last.lo[across] == f.lo[across] &&
            last.hi[across] == f.hi[across] && last.hi[along] == f.lo[along]) {
          last.hi[along] = f.hi[along];
          continue;
        }
      }
      joined.push_back(f);
    }
    open_faces_.swap(joined);
  };
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t before = open_faces_.size();
    join_along(0);
    join_along(1);
    if (open_faces_.size() == before) break;
  }
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
  // The faces are sorted by axis and plane (coalesce_open_faces() sorts them last by those).
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
    for (int a = 0; a < 3; ++a) {
      box.lo[a] = std::min(box.lo[a], b.lo[a]);
      box.hi[a] = std::max(box.hi[a], b.hi[a]);
    }
  return box;
}

Region Region::merged_with(const Region& other) const {
  if (empty()) return other;
  if (other.empty()) return *this;
  if (!(cube_ == other.cube_))
    throw InvalidArgument("region: cannot merge regions of different cubes " + cube_.to_string() + " and " +
                          other.cube_.to_string());
  std::vector<volume::Box> all = blocks_;
  all.insert(all.end(), other.blocks_.begin(), other.blocks_.end());
  Region merged(cube_, std::move(all)); // checks that the blocks are disjoint
  // A union that fills its bounding box (two brothers) is that box: one block, whose open faces
  // are whole rectangles, instead of one rectangle per face of every merged leaf (the distance to
  // the open faces is computed for every placed edge).
  const volume::Box bounds = merged.bounds();
  std::size_t cells = 0;
  for (const volume::Box& b : merged.blocks_)
    cells += b.count();
  if (cells == bounds.count()) return Region(cube_, {bounds});
  return merged;
}

std::string Region::to_string() const {
  std::string s = "cube " + cube_.to_string() + " blocks {";
  for (std::size_t i = 0; i < blocks_.size(); ++i)
    s += (i ? ", " : "") + blocks_[i].to_string();
  return s + "} open faces " + std::to_string(open_faces_.size());
}

} // namespace geotandem::tandem
