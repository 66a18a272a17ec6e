// The checks of a decoded record (surface_check.hpp). Each says which element breaks which rule,
// so that a refused record can be told from a bug of the writer.
#include "surface_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numeric>
#include <span>
#include <utility>
#include <vector>

#include "constraints.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/tandem/layer.hpp"
#include "geotandem/tandem/marching_cubes.hpp"

namespace geotandem::tandem::detail {

std::string record_blocks(const Region& region) {
  if (region.empty()) return "no blocks";
  const std::size_t n = region.blocks().size();
  return "blocks " + region.bounds().to_string() + (n > 1 ? " (" + std::to_string(n) + " blocks)" : "");
}

namespace {

// Every handle of the engine is an int: a record that would overflow one after a merge with a
// surface of the same size is refused (records are capped far below, kDefaultMaxSurface).
constexpr std::size_t kMaxElements = std::numeric_limits<std::int32_t>::max() / 8;

bool finite(const Vec3& p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

class Checker {
public:
  explicit Checker(const SurfaceState& s) : s_(s), nv_(s.points.size()) {}

  void run() {
    header();
    vertices();
    triangles();
    fans();
    components();
    edges();
    last_layer();
  }

private:
  [[noreturn]] void refuse(const std::string& what) const {
    const std::string where = record_blocks(s_.region);
    throw DataError("working-surface record: " + what, {.block = where},
                    "the record is not a partial surface of this run's extraction (forged, or damaged before its "
                    "checksum was computed): its blocks must be extracted again");
  }
  static std::string num(std::size_t i) { return std::to_string(i); }
  // activate(+inf) released every delayed edge and dropped the vertices no triangle used.
  bool past_sweep() const { return std::isinf(s_.front) && s_.front > 0.0; }

  void header() {
    if (s_.axis < 0 || s_.axis > 2) refuse("extraction axis " + std::to_string(s_.axis) + " is not 0, 1 or 2");
    const volume::Index3& shape = s_.cube.shape;
    // Lattice ids run to 4 n (edges, then border samples): n must leave room for them.
    std::uint64_t n = 1;
    for (int a = 0; a < 3; ++a) {
      if (shape[a] < 2 || shape[a] > (std::int64_t{1} << 30))
        refuse("the cube's shape " + std::to_string(shape[a]) + " along axis " + std::to_string(a) +
               " is not between 2 and 2^30 samples");
      if (n > (std::uint64_t{1} << 60) / static_cast<std::uint64_t>(shape[a]))
        refuse("the cube has more than 2^60 samples");
      n *= static_cast<std::uint64_t>(shape[a]);
    }
    samples_ = n;
    lattice_.shape = shape;
    if (s_.region.empty() || !(s_.region.cube() == cube_cells(shape)))
      refuse("its region's cube " + s_.region.cube().to_string() + " is not the cells of its cube " +
             cube_cells(shape).to_string());
    if (!(s_.options.max_error >= 0.0 && std::isfinite(s_.options.max_error)) || !std::isfinite(s_.options.isotropy))
      refuse("its simplify options are not finite (E0 " + std::to_string(s_.options.max_error) + ", alpha " +
             std::to_string(s_.options.isotropy) + ")");
    if (std::isnan(s_.front)) refuse("its front is not a number");
    if (!finite(s_.origin)) refuse("its origin is not finite");
    if (s_.vertices.size() != nv_) refuse(num(nv_) + " points but " + num(s_.vertices.size()) + " vertex records");
    if (nv_ > kMaxElements || s_.triangles.size() > kMaxElements / 3 || s_.edges.size() > kMaxElements ||
        s_.component_keys.size() > kMaxElements)
      refuse("more elements than a working surface can number");
    if (!s_.component_samples.empty() && s_.component_samples.size() != s_.component_keys.size())
      refuse(num(s_.component_keys.size()) + " components but " + num(s_.component_samples.size()) + " sample counts");
    // Positions: within the cube grown by E0 and a cell (a simplified vertex stays within E0 of the
    // marching-cubes surface, which lies inside the cube).
    const volume::Box cells = s_.region.cube();
    for (int a = 0; a < 3; ++a) {
      lo_[a] = static_cast<double>(cells.lo[a]) - 1.0 - s_.options.max_error;
      hi_[a] = static_cast<double>(cells.hi[a]) + 1.0 + s_.options.max_error;
    }
  }

  bool near_cube(const Vec3& p) const {
    for (int a = 0; a < 3; ++a)
      if (!(p[a] >= lo_[a] && p[a] <= hi_[a])) return false;
    return true;
  }

  bool on_cube_border(const Vec3& p) const {
    for (int a = 0; a < 3; ++a)
      if (p[a] == 0.0 || p[a] == static_cast<double>(s_.cube.shape[a] - 1)) return true;
    return false;
  }

  // Whether the closed blocks of the region hold p (the last block found is tried first: the
  // vertices of one block come together).
  bool in_region(const std::array<double, 3>& p) {
    const std::vector<volume::Box>& blocks = s_.region.blocks();
    auto inside = [&p](const volume::Box& b) {
      for (int a = 0; a < 3; ++a)
        if (!(p[a] >= static_cast<double>(b.lo[a]) && p[a] <= static_cast<double>(b.hi[a]))) return false;
      return true;
    };
    if (last_block_ < blocks.size() && inside(blocks[last_block_])) return true;
    for (std::size_t b = 0; b < blocks.size(); ++b)
      if (inside(blocks[b])) {
        last_block_ = b;
        return true;
      }
    return false;
  }

  // An original vertex: its lattice id names an edge of the cube (or a sample on its border, a
  // cap vertex) inside the record's blocks, and the vertex lies on it.
  void lattice_vertex(std::size_t i, std::uint64_t id) {
    const Vec3& p = s_.points[i];
    const std::string who = "vertex " + num(i) + " (lattice id " + std::to_string(id) + ")";
    std::array<double, 3> mid{};
    if (id < 3 * samples_) {
      const volume::Index3 start = lattice_.start(id);
      const int axis = lattice_.axis(id);
      if (start[axis] + 1 >= s_.cube.shape[axis]) refuse(who + ": the id names no edge of the cube");
      for (int a = 0; a < 3; ++a) {
        const auto lo = static_cast<double>(start[a]);
        const bool on = a == axis ? p[a] >= lo && p[a] <= lo + 1.0 : p[a] == lo;
        if (!on) refuse(who + ": its position is not on its lattice edge");
        mid[a] = a == axis ? lo + 0.5 : lo;
      }
    } else if (id < 4 * samples_) {
      const volume::Index3 at = lattice_.start(3 * (id - 3 * samples_));
      bool border = false;
      for (int a = 0; a < 3; ++a) {
        mid[a] = static_cast<double>(at[a]);
        if (p[a] != mid[a]) refuse(who + ": a border sample's vertex is not at its sample");
        border = border || at[a] == 0 || at[a] == s_.cube.shape[a] - 1;
      }
      if (!border) refuse(who + ": the id names a sample inside the cube, which has no vertex");
    } else {
      refuse(who + ": the id is beyond the cube's lattice");
    }
    // Integer block bounds: an edge lies in a closed block exactly when its midpoint does.
    if (!in_region(mid)) refuse(who + ": its lattice edge or sample is outside the record's blocks");
    originals_.emplace_back(id, static_cast<std::uint32_t>(i));
  }

  void vertices() {
    const std::size_t nc = s_.component_keys.size();
    min_original_.assign(nc, std::numeric_limits<std::uint64_t>::max());
    members_.assign(nc, 0);
    for (std::size_t i = 0; i < nv_; ++i) {
      const StateVertex& v = s_.vertices[i];
      const Vec3& p = s_.points[i];
      if (!finite(p)) refuse("vertex " + num(i) + " has a non-finite position");
      if (!near_cube(p)) refuse("vertex " + num(i) + " lies far outside the cube");
      if (!std::all_of(std::begin(v.shape.m), std::end(v.shape.m), [](double x) { return std::isfinite(x); }) ||
          !std::isfinite(v.height))
        refuse("vertex " + num(i) + " has a non-finite quadric or height");
      if (!(v.rad > 0.0 && std::isfinite(v.rad))) refuse("vertex " + num(i) + " has a radius that is not positive");
      if (!(v.tolerance >= 0.0 && v.tolerance <= s_.options.max_error))
        refuse("vertex " + num(i) + " has a distance bound outside [0, E0]");
      if ((v.border & ~0x3fu) != 0) refuse("vertex " + num(i) + " has border bits beyond the cube's six faces");
      if (v.component < 0 || static_cast<std::size_t>(v.component) >= nc)
        refuse("vertex " + num(i) + " belongs to component " + std::to_string(v.component) + " of " + num(nc));
      const auto c = static_cast<std::size_t>(v.component);
      ++members_[c];
      if (v.lattice_id != kNoLatticeId) {
        lattice_vertex(i, v.lattice_id);
        min_original_[c] = std::min(min_original_[c], v.lattice_id);
      }
    }
    // One vertex per lattice edge: two would weld to one and fold their triangles.
    std::sort(originals_.begin(), originals_.end());
    for (std::size_t k = 1; k < originals_.size(); ++k)
      if (originals_[k].first == originals_[k - 1].first)
        refuse("vertices " + num(originals_[k - 1].second) + " and " + num(originals_[k].second) +
               " carry the same lattice id " + std::to_string(originals_[k].first));
  }

  // Each vertex's wedges (the two other corners of its triangles, in their order), grouped by
  // vertex: wedge_[first_[v] .. first_[v + 1]).
  void triangles() {
    const std::size_t nt = s_.triangles.size();
    first_.assign(nv_ + 1, 0);
    for (std::size_t t = 0; t < nt; ++t) {
      const auto& tri = s_.triangles[t];
      for (std::uint32_t v : tri)
        if (v >= nv_) refuse("triangle " + num(t) + " refers to vertex " + std::to_string(v) + " of " + num(nv_));
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) refuse("triangle " + num(t) + " repeats a vertex");
      const std::int32_t c = s_.vertices[tri[0]].component;
      if (s_.vertices[tri[1]].component != c || s_.vertices[tri[2]].component != c)
        refuse("triangle " + num(t) + " joins different components");
      for (std::uint32_t v : tri)
        ++first_[v + 1];
    }
    std::partial_sum(first_.begin(), first_.end(), first_.begin());
    wedge_.resize(3 * nt);
    std::vector<std::size_t> at(first_.begin(), first_.end() - 1);
    for (const auto& tri : s_.triangles)
      for (int k = 0; k < 3; ++k)
        wedge_[at[tri[k]]++] = {tri[(k + 1) % 3], tri[(k + 2) % 3]};
  }

  std::span<std::pair<std::uint32_t, std::uint32_t>> wedges(std::size_t v) {
    return {wedge_.data() + first_[v], wedge_.data() + first_[v + 1]};
  }

  // The wedge around v starting at `start`, or null.
  const std::pair<std::uint32_t, std::uint32_t>* wedge_from(std::size_t v, std::uint32_t start) {
    const auto w = wedges(v);
    const auto it = std::lower_bound(w.begin(), w.end(), std::pair{start, std::uint32_t{0}});
    return it != w.end() && it->first == start ? &*it : nullptr;
  }

  // Around each vertex the wedges chain into fans: each edge once in each direction, one closed
  // fan alone or open fans only. Past the sweep, a vertex with open fans (several: a merge across a
  // block's edge leaves them until the blocks between arrive) is an original vertex on an open face,
  // or on the cube's border.
  void fans() {
    std::vector<std::uint32_t> ends;
    for (std::size_t v = 0; v < nv_; ++v) {
      const auto w = wedges(v);
      if (w.empty()) continue;
      std::sort(w.begin(), w.end());
      ends.clear();
      for (std::size_t k = 0; k < w.size(); ++k) {
        if (k > 0 && w[k].first == w[k - 1].first)
          refuse("the edge from vertex " + num(v) + " to " + std::to_string(w[k].first) +
                 " is used twice in one direction (non-manifold or misoriented)");
        ends.push_back(w[k].second);
      }
      std::sort(ends.begin(), ends.end());
      std::size_t open = 0, covered = 0;
      for (std::size_t k = 0; k < w.size(); ++k) {
        if (std::binary_search(ends.begin(), ends.end(), w[k].first)) continue;
        ++open; // a fan starts here: follow it
        for (const auto* x = &w[k]; x; x = wedge_from(v, x->second))
          if (++covered > w.size()) break;
      }
      const auto where = [&] { return "vertex " + num(v) + ": "; };
      if (open == 0) { // one closed fan, which must be all there is
        const auto* x = &w[0];
        do {
          ++covered;
          x = wedge_from(v, x->second);
        } while (x && x != &w[0] && covered <= w.size());
        if (covered != w.size()) refuse(where() + "its triangles close around it more than once");
      } else if (covered != w.size()) {
        refuse(where() + "its triangles close around it beside other fans");
      } else if (past_sweep() && !on_cube_border(s_.points[v]) &&
                 (s_.vertices[v].lattice_id == kNoLatticeId || !s_.region.on_open_face(s_.points[v]))) {
        // Past the sweep, the surface's boundary lies where a neighbour comes later (or on the
        // cube's border when there are no caps; mid-sweep also on the last layer): the vertices
        // there are original ones, which the merge welds by id.
        refuse(where() + "it is on the surface's boundary (" + num(open) +
               " open fan(s)) but is not an original vertex on an open face of the region");
      }
    }
  }

  // Every component has vertices, one connected piece of them, a key of its own no larger than
  // any of its original vertices' ids (the key is the smallest id ever born in it).
  void components() {
    const std::size_t nc = s_.component_keys.size();
    std::vector<std::uint32_t> parent(nv_);
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&parent](std::uint32_t x) {
      while (parent[x] != x)
        x = parent[x] = parent[parent[x]];
      return x;
    };
    for (const auto& tri : s_.triangles)
      for (int k = 1; k < 3; ++k) {
        const std::uint32_t a = find(tri[0]), b = find(tri[static_cast<std::size_t>(k)]);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
      }
    std::vector<std::uint32_t> piece(nc, std::numeric_limits<std::uint32_t>::max());
    for (std::size_t v = 0; v < nv_; ++v) {
      const auto c = static_cast<std::size_t>(s_.vertices[v].component);
      const std::uint32_t root = find(static_cast<std::uint32_t>(v));
      if (piece[c] == std::numeric_limits<std::uint32_t>::max()) piece[c] = root;
      if (piece[c] != root) refuse("component " + num(c) + " is made of separate pieces");
    }
    std::vector<std::pair<std::uint64_t, std::size_t>> keys;
    keys.reserve(nc);
    for (std::size_t c = 0; c < nc; ++c) {
      if (members_[c] == 0) refuse("component " + num(c) + " has no vertex");
      if (s_.component_keys[c] > min_original_[c])
        refuse("component " + num(c) + " has key " + std::to_string(s_.component_keys[c]) + ", above the lattice id " +
               std::to_string(min_original_[c]) + " of one of its vertices");
      keys.emplace_back(s_.component_keys[c], c);
    }
    std::sort(keys.begin(), keys.end());
    for (std::size_t k = 1; k < keys.size(); ++k)
      if (keys[k].first == keys[k - 1].first)
        refuse("components " + num(keys[k - 1].second) + " and " + num(keys[k].second) + " have the same key " +
               std::to_string(keys[k].first));
  }

  // The queued edges: edges of the triangles, in the writer's order (each once), in a queue with a
  // finite key; none delayed past the sweep.
  void edges() {
    front_rule_ = make_front_rule(s_.options.time_lag, s_.axis);
    face_rule_ = make_face_rule(s_.options.extended_time_lag);
    for (std::size_t i = 0; i < s_.edges.size(); ++i) {
      const StateEdge& e = s_.edges[i];
      const std::string who = "queued edge " + num(i) + " (" + std::to_string(e.v0) + ", " + std::to_string(e.v1) + ")";
      if (!(e.v0 < e.v1 && e.v1 < nv_)) refuse(who + " is not a pair of distinct vertices in increasing order");
      if (i > 0 && !(std::pair(s_.edges[i - 1].v0, s_.edges[i - 1].v1) < std::pair(e.v0, e.v1)))
        refuse(who + " is listed twice or out of order");
      if (!wedge_from(e.v0, e.v1) && !wedge_from(e.v1, e.v0)) refuse(who + " is not an edge of the triangles");
      if (e.state == EdgeState::idle) refuse(who + " is idle (idle edges are not written)");
      if (!std::isfinite(e.key)) refuse(who + " has a non-finite key");
      if (e.state == EdgeState::delayed && past_sweep()) refuse(who + " is delayed past the sweep");
      if (e.state == EdgeState::candidate && !near_cube(e.pending.target))
        refuse(who + " has a candidate position that is not finite or lies far outside the cube");
      // Q holds only edges the front and the open faces let collapse (Collapser::place): a candidate
      // they hold back would collapse a vertex a neighbour is to weld to (the record's region's
      // open faces include every open face of a merge's union near its edges).
      if (e.state == EdgeState::candidate) {
        EdgeGeometry g;
        g.a = s_.points[e.v0];
        g.b = s_.points[e.v1];
        g.height_a = s_.vertices[e.v0].height;
        g.height_b = s_.vertices[e.v1].height;
        g.rad_a = s_.vertices[e.v0].rad;
        g.rad_b = s_.vertices[e.v1].rad;
        if (!(front_rule_->key(g) < s_.front) || face_rule_->holding_face(g, s_.region).index >= 0)
          refuse(who + " is a candidate that the front or the region's open faces hold back");
      }
    }
  }

  // The last layer's ids name vertices; the isolated vertices (mid-sweep only) have
  // no triangle; a vertex without triangles is one of them.
  void last_layer() {
    if (past_sweep() && !s_.isolated.empty()) refuse("it is past its sweep but still lists isolated vertices");
    for (std::size_t k = 0; k < s_.previous_ids.size(); ++k) {
      const auto& [id, v] = s_.previous_ids[k];
      // The vertex may have been simplified since (its id is gone): a layer repeating the id then
      // fails (add_layer), as it would in the sender.
      if (v >= nv_ || id == kNoLatticeId)
        refuse("last-layer id " + std::to_string(id) + " names no vertex of the " + num(nv_));
      if (k > 0 && !(s_.previous_ids[k - 1].first < id)) refuse("last-layer id " + std::to_string(id) + " repeats");
    }
    std::vector<bool> isolated(nv_, false);
    for (std::uint32_t v : s_.isolated) {
      if (v >= nv_ || isolated[v] || first_[v] != first_[v + 1])
        refuse("isolated vertex " + std::to_string(v) + " is out of range, repeated or has triangles");
      isolated[v] = true;
    }
    for (std::size_t v = 0; v < nv_; ++v)
      if (first_[v] == first_[v + 1] && !isolated[v]) refuse("vertex " + num(v) + " has no triangle");
  }

  const SurfaceState& s_;
  const std::size_t nv_;
  std::uint64_t samples_ = 0;
  LatticeIds lattice_;
  std::array<double, 3> lo_{}, hi_{};
  std::size_t last_block_ = 0;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> originals_; // lattice id, vertex
  std::vector<std::uint64_t> min_original_;                        // per component
  std::vector<std::size_t> members_;                               // per component
  std::vector<std::size_t> first_;
  std::unique_ptr<FrontRule> front_rule_;
  std::unique_ptr<FaceRule> face_rule_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> wedge_;
};

} // namespace

void check_state(const SurfaceState& s) {
  Checker(s).run();
}

} // namespace geotandem::tandem::detail
