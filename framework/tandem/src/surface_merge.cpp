// Merging two partial surfaces of adjacent regions (the seed's section 3.2; ALGORITHM.md, "Blocks
// and merging"): the other surface's vertices, triangles and queue states are appended to this
// one, vertices on the common faces welded by lattice-edge id, quadrics, heights and radii kept,
// components joined through the seam. The caller then tests the parked edges against the merged
// region, simplifies and dumps (WorkingSurface::merge). Appending in place costs O(other); the
// larger surface absorbs the smaller.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "geotandem/core/error.hpp"
#include "surface_check.hpp"
#include "surface_engine.hpp"
#include "triangle_insert.hpp"

namespace geotandem::tandem {

namespace {

bool same_options(const SimplifyOptions& a, const SimplifyOptions& b) {
  return a.max_error == b.max_error && a.isotropy == b.isotropy && a.time_lag == b.time_lag &&
         a.extended_time_lag == b.extended_time_lag && a.preserve_volume == b.preserve_volume &&
         a.guarantee_distance == b.guarantee_distance;
}

std::string where(const Region& a, const Region& b) {
  return "merging {" + a.to_string() + "} with {" + b.to_string() + "}";
}

} // namespace

// The same grid, whatever CRS each side names: the CRS changes no vertex, and the working-surface
// wire form (surface_wire.cpp) does not carry it, so a surface decoded from another block or worker
// has none while this process's volume may.
Region WorkingSurface::Engine::merge_region(const Engine& b) const {
  if (!cube_.same_grid(b.cube_))
    throw InvalidArgument("merge: the two surfaces belong to different cubes", {.block = b.region_.to_string()});
  return merge_region_of(b.region_, b.axis_, b.collapser_.options(), b.front());
}

Region WorkingSurface::Engine::merge_region_state(const detail::SurfaceState& b) const {
  if (!cube_.same_grid(b.cube))
    throw InvalidArgument("merge: the two surfaces belong to different cubes", {.block = b.region.to_string()});
  return merge_region_of(b.region, b.axis, b.options, b.front);
}

Region WorkingSurface::Engine::merge_region_of(const Region& region, int axis, const SimplifyOptions& options,
                                               double front) const {
  if (axis_ != axis)
    throw InvalidArgument("merge: the surfaces were extracted along axes " + std::to_string(axis_) + " and " +
                          std::to_string(axis));
  if (!same_options(collapser_.options(), options))
    throw InvalidArgument("merge: the surfaces were simplified with different options (E0, alpha, time lags)", {},
                          "extract every block with the same SimplifyOptions");
  if (!std::isinf(this->front()) || !std::isinf(front) || this->front() < 0.0 || front < 0.0)
    throw InvalidArgument("merge: both surfaces must be past their sweep", {.block = region.to_string()},
                          "run the last layer and activate(+inf) (run_tandem does) before merging");
  return region_.merged_with(region); // throws when the blocks overlap
}

std::size_t WorkingSurface::Engine::merge_state(detail::SurfaceState&& other, const CancelToken* cancel) {
  const Region before = region_;
  absorb_state(std::move(other));        // gives the state's parts back before the simplification
  collapser_.place_parked_again(before); // the region grew: edges parked by faces it closed are placed again
  simplify(cancel);
  return dump();
}

void WorkingSurface::Engine::absorb_state(detail::SurfaceState&& t) {
  const Region region = merge_region_state(t);
  // Only for a message: a worker's region can hold thousands of blocks.
  const auto where_text = [&] { return where(region_, t.region); };
  const std::size_t nb = t.points.size(), nt = t.triangles.size();

  // Lattice id -> live original vertex of this surface. A lattice edge both sides share lies in
  // the other side's blocks (closed), and so does the vertex on it: the positions are read first,
  // and only the few vertices there are looked at (this side may hold a large part of the cube).
  detail::IdMap ids;
  {
    const volume::Box there = t.region.bounds();
    std::array<double, 3> lo{}, hi{};
    for (int a = 0; a < 3; ++a) {
      lo[a] = static_cast<double>(there.lo[a]) - 0.5;
      hi[a] = static_cast<double>(there.hi[a]) + 0.5;
    }
    const detail::HalfedgeMesh& mesh = storage_.mesh();
    for (std::size_t i = 0; i < mesh.n_vertices(); ++i) {
      const auto& p = mesh.points()[i];
      if (p[0] < lo[0] || p[0] > hi[0] || p[1] < lo[1] || p[1] > hi[1] || p[2] < lo[2] || p[2] > hi[2]) continue;
      const detail::VertexRecord& r = mesh.vertex_records()[i];
      if (r.alive && r.lattice_id != detail::kNoLatticeId) ids.insert(r.lattice_id, static_cast<std::int32_t>(i));
    }
  }

  // Vertices: welded to an original vertex with the same lattice id, or appended. Nothing of this
  // surface changes until the weld is known to fit (the state itself was checked when its record
  // was decoded, check_state): a welded vertex is at the same position to the bit (both blocks
  // interpolate from the edge's lower end) and on this side's boundary, and no triangle of the
  // other side uses an edge between welded vertices in the direction this side's triangles do.
  std::vector<VH> vertex(nb);
  detail::HalfedgeMesh& mesh = storage_.mesh();
  const std::size_t first_new = mesh.n_vertices(), edges_before = mesh.n_edges(), faces_before = mesh.n_faces();
  std::size_t next = first_new;
  for (std::size_t i = 0; i < nb; ++i) {
    const detail::StateVertex& r = t.vertices[i];
    if (r.component < 0 || static_cast<std::size_t>(r.component) >= t.component_keys.size())
      throw DataError(where_text() + ": vertex " + std::to_string(i) + " of the other side has no component");
    const std::int32_t j = r.lattice_id == detail::kNoLatticeId ? -1 : ids.find(r.lattice_id);
    if (j < 0) {
      vertex[i] = VH(static_cast<int>(next++));
      continue;
    }
    vertex[i] = VH(j);
    const detail::Vec3 p = storage_.position(vertex[i]);
    if (p != t.points[i]) // computed the same way on both sides: equal to the last bit
      throw DataError(
          where_text() + ": lattice edge " + std::to_string(r.lattice_id) + " has different positions on the two sides",
          {.block = detail::record_blocks(t.region)}, "both blocks must come from the same volume and isovalue");
    if (!mesh.is_boundary(vertex[i]) || mesh.is_isolated(vertex[i]))
      throw DataError(where_text() + ": lattice edge " + std::to_string(r.lattice_id) +
                          " is not on this side's boundary, where the other side would weld to it",
                      {.block = detail::record_blocks(t.region)},
                      "the two surfaces must be the partial surfaces of adjacent blocks of one extraction");
  }
  for (std::size_t k = 0; k < nt; ++k) {
    const auto& tri = t.triangles[k];
    for (int c = 0; c < 3; ++c) {
      const VH a = vertex[tri[static_cast<std::size_t>(c)]], b = vertex[tri[static_cast<std::size_t>((c + 1) % 3)]];
      if (static_cast<std::size_t>(a.idx()) >= first_new || static_cast<std::size_t>(b.idx()) >= first_new) continue;
      const HH h = detail::find_halfedge(mesh, a, b);
      if (h.is_valid() && !mesh.is_boundary(h))
        throw DataError(where_text() + ": triangle " + std::to_string(k) +
                            " of the other side uses a seam edge in the direction of this side's triangle",
                        {.block = detail::record_blocks(t.region)},
                        "the two surfaces must be the partial surfaces of adjacent blocks of one extraction");
    }
  }
  // Handles are ints: the merged mesh must be numbered by them.
  constexpr std::size_t kMaxHandle = static_cast<std::size_t>(std::numeric_limits<int>::max()) / 2;
  if (next > kMaxHandle || edges_before + 3 * nt > kMaxHandle || faces_before + nt > kMaxHandle)
    throw DataError(where_text() + ": the merged surface would hold more elements than a working surface can number",
                    {.block = detail::record_blocks(t.region)}, "use smaller blocks");

  // The other side's components join the table; those the seam touches are united below.
  detail::ComponentTable& components = storage_.components();
  std::vector<std::int32_t> component(t.component_keys.size());
  for (std::size_t c = 0; c < component.size(); ++c)
    component[c] =
        components.create(t.component_keys[c], -1, c < t.component_samples.size() ? t.component_samples[c] : 0);
  // Exactly the room the merge may need: the larger surface does not double its storage for it.
  storage_.begin_append(next - first_new, nt, true);
  for (std::size_t i = 0; i < nb; ++i) {
    const detail::StateVertex& r = t.vertices[i];
    const VH v = vertex[i];
    const std::int32_t c = component[static_cast<std::size_t>(r.component)];
    detail::VertexRecord& w = storage_.vertex(v);
    if (static_cast<std::size_t>(v.idx()) >= first_new) {
      w = detail::vertex_record(r, c); // its face sums are added from this side's origin below
      storage_.set_position(v, t.points[i]);
    } else {
      // The same lattice edge seen from both sides: one vertex (positions compared above). Both
      // are original marching-cubes vertices (height = rank at birth, rad = 1).
      w.shape += r.shape;
      w.border |= r.border;
      w.version = std::max(w.version, r.version) + 1; // candidates computed on either side are stale
      components.unite(w.component, c);
    }
    detail::ComponentRecord& cr = components.at(c);
    if (cr.member < 0) cr.member = v.idx();
  }

  std::vector<detail::Vec3>().swap(t.points);
  std::vector<detail::StateVertex>().swap(t.vertices);

  // Triangles: the seam's boundary edges, present on both sides, become interior edges.
  std::vector<FH> faces;
  faces.reserve(nt);
  for (std::size_t k = 0; k < nt; ++k) {
    const auto& tri = t.triangles[k];
    const FH f = storage_.add_triangle(vertex[tri[0]], vertex[tri[1]], vertex[tri[2]]);
    if (!f.is_valid())
      throw DataError(where_text() + ": triangle " + std::to_string(k) +
                          " of the other side would make the surface non-manifold",
                      {.block = detail::record_blocks(t.region)},
                      "the two surfaces must be the partial surfaces of adjacent blocks of one extraction");
    faces.push_back(f);
  }
  std::vector<std::array<std::uint32_t, 3>>().swap(t.triangles);
  storage_.end_append();
  collapser_.grown();
  // The other side's face terms were relative to its own origin: computed again from this one's,
  // which also completes the sums of the welded vertices.
  collapser_.add_faces(faces);

  // The other side's queue states (the seam's edges are parked on both sides).
  for (std::size_t i = 0; i < t.edges.size(); ++i)
    collapser_.restore_edge(vertex[t.edges[i].v0], vertex[t.edges[i].v1], t.edges[i], i);
  std::vector<detail::StateEdge>().swap(t.edges);

  collapser_.counters() += t.counters;
  last_rank_ = std::max(last_rank_, t.last_rank);
  region_ = region;
  // Any component of the other side may be finished now (its waiting edges were re-counted).
  for (std::int32_t id : component)
    components.requeue(components.find(id));
}

} // namespace geotandem::tandem
