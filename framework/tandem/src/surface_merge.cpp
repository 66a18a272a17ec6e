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

// The open face of `after` that still holds back a parked edge whose record names a face of
// `before` and a square of it, or -1 when none does or either is not known. `kept`:
// before.open_faces_kept_in(after).
int face_after_merge(const detail::EdgeRecord& r, const std::vector<int>& kept, const Region& before,
                     const Region& after) {
  if (r.face == detail::kUnknownFace || r.face >= kept.size()) return -1;
  if (kept[r.face] >= 0 || r.pending_or_square == detail::kUnknownSquare) return kept[r.face];
  OpenFace square = before.open_faces()[r.face];
  square.lo = detail::square_corner(r.pending_or_square);
  square.hi = {square.lo[0] + 1.0, square.lo[1] + 1.0};
  return after.open_face_holding(square);
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
  return merge_region_of(b.region_, b.axis_, b.options_, b.front_);
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
  if (!same_options(options_, options))
    throw InvalidArgument("merge: the surfaces were simplified with different options (E0, alpha, time lags)", {},
                          "extract every block with the same SimplifyOptions");
  if (!std::isinf(front_) || !std::isinf(front) || front_ < 0.0 || front < 0.0)
    throw InvalidArgument("merge: both surfaces must be past their sweep", {.block = region.to_string()},
                          "run the last layer and activate(+inf) (run_tandem does) before merging");
  return region_.merged_with(region); // throws when the blocks overlap
}

std::size_t WorkingSurface::Engine::merge_state(detail::SurfaceState&& other, const CancelToken* cancel) {
  const Region before = region_;
  absorb_state(std::move(other)); // gives the state's parts back before the simplification
  place_parked_again(before);     // the region grew: edges parked by faces it closed are placed again
  simplify(cancel);
  return dump();
}

void WorkingSurface::Engine::place_parked_again(const Region& before) {
  // A parked edge's ball reaches the face its record names, at a point in the square it names.
  // When the grown region still has that square open (inside one of its open faces: the whole
  // face when it is kept, the usual case), the ball still reaches an open face and placing the
  // edge again would only park it again with the same key: it is skipped, and its face
  // renumbered. The others (and those not known: the other side's) are placed again in list
  // order, as placing every parked edge would (the same queues, to the bit).
  const std::vector<int> kept = before.open_faces_kept_in(region_);
  std::vector<std::int32_t> again;
  for (std::int32_t e : queues_.parked()) {
    detail::EdgeRecord& r = erec_[static_cast<std::size_t>(e)];
    const int face = face_after_merge(r, kept, before, region_);
    if (face >= 0 && face < detail::kUnknownFace) {
      r.face = static_cast<std::uint16_t>(face);
    } else {
      r.face = detail::kUnknownFace;
      again.push_back(e);
    }
  }
  for (std::int32_t e : again)
    place(EH(e));
}

void WorkingSurface::Engine::find_parked_faces() {
  for (std::int32_t e : queues_.parked()) {
    detail::EdgeRecord& r = erec_[static_cast<std::size_t>(e)];
    if (r.face != detail::kUnknownFace) continue;
    const Region::NearestFace hold = face_rule_->holding_face(geometry_of(mesh_->halfedge_handle(EH(e), 0)), region_);
    detail::EdgeQueues::hold_at(r, &hold);
  }
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
    for (std::size_t i = 0; i < mesh_->n_vertices(); ++i) {
      const auto& p = points_[i];
      if (p[0] < lo[0] || p[0] > hi[0] || p[1] < lo[1] || p[1] > hi[1] || p[2] < lo[2] || p[2] > hi[2]) continue;
      if (vrec_[i].alive && vrec_[i].lattice_id != detail::kNoLatticeId)
        ids.insert(vrec_[i].lattice_id, static_cast<std::int32_t>(i));
    }
  }

  // Vertices: welded to an original vertex with the same lattice id, or appended. Nothing of this
  // surface changes until the weld is known to fit (the state itself was checked when its record
  // was decoded, check_state): a welded vertex is at the same position to the bit (both blocks
  // interpolate from the edge's lower end) and on this side's boundary, and no triangle of the
  // other side uses an edge between welded vertices in the direction this side's triangles do.
  std::vector<VH> vertex(nb);
  const std::size_t first_new = mesh_->n_vertices(), edges_before = mesh_->n_edges(), faces_before = mesh_->n_faces();
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
    const detail::Vec3 p = position(vertex[i]);
    if (p != t.points[i]) // computed the same way on both sides: equal to the last bit
      throw DataError(
          where_text() + ": lattice edge " + std::to_string(r.lattice_id) + " has different positions on the two sides",
          {.block = detail::record_blocks(t.region)}, "both blocks must come from the same volume and isovalue");
    if (!mesh_->is_boundary(vertex[i]) || mesh_->is_isolated(vertex[i]))
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
      const HH h = detail::find_halfedge(*mesh_, a, b);
      if (h.is_valid() && !mesh_->is_boundary(h))
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
  std::vector<std::int32_t> component(t.component_keys.size());
  for (std::size_t c = 0; c < component.size(); ++c)
    component[c] =
        components_.create(t.component_keys[c], -1, c < t.component_samples.size() ? t.component_samples[c] : 0);
  // Exactly the room the merge may need: the larger surface does not double its storage for it.
  // Edges and faces are appended as the triangles go in: the room they do not use is not touched.
  mesh_->reserve(next, edges_before + 3 * nt, faces_before + nt);
  mesh_->resize(next, edges_before, faces_before);
  refresh();
  for (std::size_t i = 0; i < nb; ++i) {
    const detail::StateVertex& r = t.vertices[i];
    const VH v = vertex[i];
    const std::int32_t c = component[static_cast<std::size_t>(r.component)];
    detail::VertexRecord& w = vrec(v);
    if (static_cast<std::size_t>(v.idx()) >= first_new) {
      w = detail::vertex_record(r, c); // its face sums are added from this side's origin below
      points_[v.idx()] = detail::HalfedgeMesh::Point(t.points[i][0], t.points[i][1], t.points[i][2]);
      ++live_vertices_;
    } else {
      // The same lattice edge seen from both sides: one vertex (positions compared above). Both
      // are original marching-cubes vertices (height = rank at birth, rad = 1).
      w.shape += r.shape;
      w.border |= r.border;
      w.version = std::max(w.version, r.version) + 1; // candidates computed on either side are stale
      components_.unite(w.component, c);
    }
    detail::ComponentRecord& cr = components_.at(c);
    if (cr.member < 0) cr.member = v.idx();
  }

  std::vector<detail::Vec3>().swap(t.points);
  std::vector<detail::StateVertex>().swap(t.vertices);

  // Triangles: the seam's boundary edges, present on both sides, become interior edges.
  std::vector<FH> faces;
  faces.reserve(nt);
  for (std::size_t k = 0; k < nt; ++k) {
    const auto& tri = t.triangles[k];
    const FH f = detail::insert_triangle(*mesh_, vertex[tri[0]], vertex[tri[1]], vertex[tri[2]]);
    if (!f.is_valid())
      throw DataError(where_text() + ": triangle " + std::to_string(k) +
                          " of the other side would make the surface non-manifold",
                      {.block = detail::record_blocks(t.region)},
                      "the two surfaces must be the partial surfaces of adjacent blocks of one extraction");
    faces.push_back(f);
  }
  std::vector<std::array<std::uint32_t, 3>>().swap(t.triangles);
  refresh();
  for (std::size_t i = edges_before; i < mesh_->n_edges(); ++i) {
    erec_[i] = detail::EdgeRecord{};
    erec_[i].alive = true;
  }
  // The other side's face terms were relative to its own origin: computed again from this one's,
  // which also completes the sums of the welded vertices.
  for (FH f : faces)
    costs_.add_face_terms(f);
  live_faces_ += nt;

  // The other side's queue states (the seam's edges are parked on both sides).
  for (std::size_t i = 0; i < t.edges.size(); ++i)
    restore_edge(vertex[t.edges[i].v0], vertex[t.edges[i].v1], t.edges[i], i);
  std::vector<detail::StateEdge>().swap(t.edges);

  counters_ += t.counters;
  last_rank_ = std::max(last_rank_, t.last_rank);
  region_ = region;
  // Any component of the other side may be finished now (its waiting edges were re-counted).
  for (std::int32_t id : component)
    components_.requeue(components_.find(id));
}

} // namespace geotandem::tandem
