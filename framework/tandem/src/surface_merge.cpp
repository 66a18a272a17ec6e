// Merging two partial surfaces of adjacent regions (the seed's section 3.2; ALGORITHM.md, "Blocks
// and merging"): the union of the meshes, vertices on the common faces welded by lattice-edge id,
// quadrics, heights and radii kept, components joined through the seam. The caller then tests
// the parked edges against the merged region, simplifies and dumps (WorkingSurface::merge).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "geotandem/core/error.hpp"
#include "surface_engine.hpp"

namespace geotandem::tandem {

namespace {

bool same_options(const SimplifyOptions& a, const SimplifyOptions& b) {
  return a.max_error == b.max_error && a.isotropy == b.isotropy && a.time_lag == b.time_lag &&
         a.extended_time_lag == b.extended_time_lag && a.preserve_volume == b.preserve_volume;
}

// Union-find over the components of both sides, to join those the seam connects.
struct Joiner {
  std::vector<std::int32_t> parent;
  std::int32_t find(std::int32_t c) {
    while (parent[static_cast<std::size_t>(c)] != c) {
      parent[static_cast<std::size_t>(c)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(c)])];
      c = parent[static_cast<std::size_t>(c)];
    }
    return c;
  }
  void unite(std::int32_t a, std::int32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (a > b) std::swap(a, b);
    parent[static_cast<std::size_t>(b)] = a;
  }
};

std::string where(const Region& a, const Region& b) {
  return "merging {" + a.to_string() + "} with {" + b.to_string() + "}";
}

} // namespace

std::unique_ptr<WorkingSurface::Engine> WorkingSurface::Engine::merged(const Engine& a, const Engine& b) {
  if (!(a.cube_ == b.cube_))
    throw InvalidArgument("merge: the two surfaces belong to different cubes", {.block = b.region_.to_string()});
  if (a.axis_ != b.axis_)
    throw InvalidArgument("merge: the surfaces were extracted along axes " + std::to_string(a.axis_) + " and " +
                          std::to_string(b.axis_));
  if (!same_options(a.options_, b.options_))
    throw InvalidArgument("merge: the surfaces were simplified with different options (E0, alpha, time lags)", {},
                          "extract every block with the same SimplifyOptions");
  if (!std::isinf(a.front_) || !std::isinf(b.front_) || a.front_ < 0.0 || b.front_ < 0.0)
    throw InvalidArgument("merge: both surfaces must be past their sweep", {.block = b.region_.to_string()},
                          "run the last layer and activate(+inf) (run_tandem does) before merging");
  const Region region = a.region_.merged_with(b.region_); // throws when the blocks overlap

  detail::SurfaceState s = a.export_state();
  detail::SurfaceState t = b.export_state();
  const std::size_t na = s.points.size();
  const auto ca = static_cast<std::int32_t>(s.component_keys.size());

  // Lattice id -> vertex of a, for the original marching-cubes vertices (those on open faces are
  // the ones b can share).
  detail::IdMap ids;
  for (std::size_t i = 0; i < na; ++i)
    if (s.vertices[i].lattice_id != detail::kNoLatticeId)
      ids.insert(s.vertices[i].lattice_id, static_cast<std::int32_t>(i));

  Joiner join;
  join.parent.resize(s.component_keys.size() + t.component_keys.size());
  for (std::size_t c = 0; c < join.parent.size(); ++c)
    join.parent[c] = static_cast<std::int32_t>(c);

  std::vector<std::uint32_t> map(t.points.size());
  for (std::size_t i = 0; i < t.points.size(); ++i) {
    detail::VertexRecord r = t.vertices[i];
    r.component += ca;
    const std::int32_t j = r.lattice_id == detail::kNoLatticeId ? -1 : ids.find(r.lattice_id);
    if (j < 0) {
      map[i] = static_cast<std::uint32_t>(s.points.size());
      s.points.push_back(t.points[i]);
      s.vertices.push_back(r);
      continue;
    }
    // The same lattice edge seen from both sides: one vertex. Both are original marching-cubes
    // vertices (height = rank at birth, rad = 1); positions are interpolated from the edge's
    // lower end by both blocks, so they must agree to the bit.
    detail::VertexRecord& w = s.vertices[static_cast<std::size_t>(j)];
    if (std::memcmp(s.points[static_cast<std::size_t>(j)].data(), t.points[i].data(), sizeof(detail::Vec3)) != 0)
      throw DataError(where(a.region_, b.region_) + ": lattice edge " + std::to_string(r.lattice_id) +
                          " has different positions on the two sides",
                      {.block = b.region_.to_string()}, "both blocks must come from the same volume and isovalue");
    w.shape += r.shape;
    w.weight += r.weight;
    w.border |= r.border;
    w.version = std::max(w.version, r.version) + 1; // candidates computed on either side are stale
    join.unite(w.component, r.component);
    map[i] = static_cast<std::uint32_t>(j);
  }
  for (std::size_t k = 0; k < t.triangles.size(); ++k) {
    const auto& tri = t.triangles[k];
    s.triangles.push_back({map[tri[0]], map[tri[1]], map[tri[2]]});
    s.faces.push_back(t.faces[k]);
  }
  for (detail::StateEdge e : t.edges) {
    e.v0 = map[e.v0];
    e.v1 = map[e.v1];
    s.edges.push_back(e);
  }

  // Components: the roots of the union, renumbered in order, keeping the smallest key.
  std::vector<std::uint64_t> keys = s.component_keys;
  keys.insert(keys.end(), t.component_keys.begin(), t.component_keys.end());
  std::vector<std::int32_t> renumber(keys.size(), -1);
  std::vector<std::uint64_t> merged_keys;
  for (std::size_t c = 0; c < keys.size(); ++c) {
    const auto root = static_cast<std::size_t>(join.find(static_cast<std::int32_t>(c)));
    if (renumber[root] < 0) {
      renumber[root] = static_cast<std::int32_t>(merged_keys.size());
      merged_keys.push_back(keys[root]);
    }
    std::uint64_t& key = merged_keys[static_cast<std::size_t>(renumber[root])];
    key = std::min(key, keys[c]);
    renumber[c] = renumber[root];
  }
  for (detail::VertexRecord& r : s.vertices)
    r.component = renumber[static_cast<std::size_t>(r.component)];
  s.component_keys = std::move(merged_keys);

  // Counters add up; the candidates of both sides are stale where they touch the seam.
  SimplifyCounters& c = s.counters;
  const SimplifyCounters& o = t.counters;
  c.input_triangles += o.input_triangles;
  c.collapses += o.collapses;
  c.evaluations += o.evaluations;
  c.rejected_shape += o.rejected_shape;
  c.rejected_link += o.rejected_link;
  c.rejected_flip += o.rejected_flip;
  c.rejected_border += o.rejected_border;
  c.retried += o.retried;
  c.distrusted += o.distrusted;
  c.blocked_by_faces += o.blocked_by_faces;
  c.components_dumped += o.components_dumped;
  c.triangles_dumped += o.triangles_dumped;
  c.garbage_collections += o.garbage_collections;
  s.last_rank = std::max(s.last_rank, t.last_rank);
  s.region = region;
  s.previous_ids.clear();
  s.isolated.clear();

  auto out = std::make_unique<Engine>(a.cube_, region, a.axis_, a.options_, a.sink_, a.observer_);
  try {
    out->import_state(std::move(s));
  } catch (const DataError& e) {
    throw DataError(where(a.region_, b.region_) + ": " + e.message(), {.block = b.region_.to_string()},
                    "the two surfaces must be the partial surfaces of adjacent blocks of one extraction");
  }
  // The volume and isotropy terms were taken from each side's origin, and the welded vertices
  // have triangles of both sides: compute them again.
  out->recompute_face_terms();
  return out;
}

} // namespace geotandem::tandem
