#include "surface_engine.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "geotandem/core/error.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "spare_meshes.hpp"

namespace geotandem::tandem {

using detail::Candidate;
using detail::CostInputs;
using detail::EdgeGeometry;
using detail::EdgeState;
using detail::Vec3;
using detail::operator+;
using detail::operator-;
using detail::operator*;

namespace {
// The cube's last sample index on each axis: the far faces a border vertex stays on.
std::array<double, 3> last_indices(const volume::Geometry& cube) {
  std::array<double, 3> hi{};
  for (int i = 0; i < 3; ++i)
    hi[static_cast<std::size_t>(i)] = static_cast<double>(cube.shape[i] - 1);
  return hi;
}
} // namespace

WorkingSurface::Engine::~Engine() {
  detail::keep_spare_mesh(std::move(mesh_), region_.blocks().size() == 1);
}

WorkingSurface::Engine::Engine(const volume::Geometry& cube, Region region, int axis, const SimplifyOptions& options,
                               mesh::ComponentSink* sink, CollapseObserver* observer)
    : cube_(cube), region_(std::move(region)), axis_(axis), options_(options), sink_(sink), observer_(observer),
      cube_hi_(last_indices(cube)), front_rule_(detail::make_front_rule(options.time_lag, axis)),
      face_rule_(detail::make_face_rule(options.extended_time_lag)), mesh_(detail::take_spare_mesh()),
      costs_(*mesh_, options, cube_hi_) {
  options_.validate();
  cube_.validate();
  if (axis < 0 || axis > 2)
    throw InvalidArgument("working surface: extraction axis " + std::to_string(axis) + " is not 0, 1 or 2");
  const volume::Box cells = cube_cells(cube_.shape);
  if (region_.empty()) region_ = Region::block(cells, cells);
  if (!(region_.cube() == cells))
    throw InvalidArgument("working surface: the region's cube " + region_.cube().to_string() +
                              " is not the cells of the cube " + cells.to_string(),
                          {}, "build the region from cube_cells(geometry.shape)");
  lattice_.shape = cube_.shape;
  detail::Vec3 origin;
  for (std::size_t i = 0; i < 3; ++i)
    origin[i] = static_cast<double>(region_.blocks().front().lo[i]);
  costs_.set_origin(origin);
  refresh();
}

void WorkingSurface::Engine::refresh() {
  vrec_ = mesh_->vertex_records();
  erec_ = mesh_->edge_records();
  frec_ = mesh_->face_records();
  points_ = mesh_->points();
  costs_.refresh(vrec_, points_);
  queues_.ensure_slots(mesh_->n_edges());
  marks_.ensure(mesh_->n_vertices());
}

// ---------------------------------------------------------------------------------------------
// Queues

detail::EdgeGeometry WorkingSurface::Engine::geometry_of(HH h) const {
  const VH a = mesh_->from_vertex_handle(h), b = mesh_->to_vertex_handle(h);
  const detail::VertexRecord& ra = vrec_[a.idx()];
  const detail::VertexRecord& rb = vrec_[b.idx()];
  EdgeGeometry g;
  g.a = position(a);
  g.b = position(b);
  g.height_a = ra.height;
  g.height_b = rb.height;
  g.rad_a = ra.rad;
  g.rad_b = rb.rad;
  return g;
}

void WorkingSurface::Engine::set_state(EH e, EdgeState state, double key, const Region::NearestFace* hold) {
  if (queues_.move(erec(e), static_cast<std::int32_t>(e.idx()), state, key, hold)) {
    const VH a = mesh_->to_vertex_handle(mesh_->halfedge_handle(e, 0));
    components_.add_waiting(vrec(a).component, detail::waiting(state) ? 1 : -1);
  }
}

void WorkingSurface::Engine::enqueue(EH e, double cost, const detail::Vec3& target, bool retried) {
  set_state(e, EdgeState::candidate, cost);
  detail::Pending& p = pending(e);
  p.target = target;
  p.stamp = stamp_of(e);
  p.retried = retried;
  p.dirty = false;
}

std::uint32_t WorkingSurface::Engine::stamp_of(EH e) const {
  const HH h = mesh_->halfedge_handle(e, 0);
  return vrec_[mesh_->from_vertex_handle(h).idx()].version + vrec_[mesh_->to_vertex_handle(h).idx()].version;
}

void WorkingSurface::Engine::place(EH e) {
  const HH h = mesh_->halfedge_handle(e, 0);
  const EdgeGeometry g = geometry_of(h);
  const double lag = front_rule_->key(g);
  if (!(lag < front_)) {
    set_state(e, EdgeState::delayed, lag);
    return;
  }
  const Region::NearestFace hold = face_rule_->holding_face(g, region_);
  if (hold.index >= 0) {
    ++counters_.blocked_by_faces;
    set_state(e, EdgeState::parked, lag, &hold);
    return;
  }
  // Lazy evaluation: a candidate keeps its old key, now stale, and is evaluated again when it
  // reaches the top of Q (put back if it became dearer). Costs mostly grow as patches merge, so
  // the old key is nearly always a lower bound and the order stays the greedy one.
  // (The stamp cannot tell: an edge that lost a to c has new endpoints, whose versions may sum to
  // the old value.)
  if (erec(e).state == EdgeState::candidate) {
    pending(e).dirty = true;
    return;
  }
  Candidate c;
  if (costs_.evaluate(h, c, counters_)) {
    enqueue(e, c.cost, c.position, false);
  } else {
    set_state(e, EdgeState::idle, 0.0);
  }
}

void WorkingSurface::Engine::activate(double front) {
  if (front < front_)
    throw InvalidArgument("working surface: the front cannot move back from " + std::to_string(front_) + " to " +
                          std::to_string(front));
  front_ = front;
  if (std::isinf(front_)) drop_isolated_vertices(); // no layer will use them now
  std::vector<std::int32_t> bucket;
  while (queues_.delayed_below(front_, bucket)) {
    bool moved = false;
    for (std::int32_t e : bucket) {
      if (!(erec_[e].key < front_)) continue;
      place(EH(e));
      moved = true;
    }
    if (!moved) break; // the lowest bucket only holds keys at or above the front
  }
}

void WorkingSurface::Engine::set_region(Region region) {
  if (!(region.cube() == region_.cube()))
    throw InvalidArgument("working surface: the new region " + region.to_string() + " is not in the same cube as " +
                          region_.to_string());
  region_ = std::move(region);
  const std::vector<std::int32_t> parked = queues_.parked();
  for (std::int32_t e : parked)
    place(EH(e));
}

// ---------------------------------------------------------------------------------------------
// Collapses

void WorkingSurface::Engine::simplify(const CancelToken* cancel) {
  std::uint32_t steps = 0;
  while (queues_.has_candidates()) {
    if (cancel && (++steps & 0xFFFu) == 0) cancel->throw_if_cancelled();
    const EH e(queues_.cheapest().item);
    const double key = queues_.cheapest().key;
    const detail::Pending p = pending(e); // a copy: leaving Q frees its place
    set_state(e, EdgeState::idle, 0.0);
    if (p.dirty || p.stamp != stamp_of(e)) {
      // Collapses nearby changed what its cost depends on: compute it again, and put it back
      // when it became dearer.
      Candidate c;
      CostInputs in;
      if (!costs_.evaluate(mesh_->halfedge_handle(e, 0), c, counters_, in)) continue;
      if (c.cost > key + 1e-12 * (1.0 + key)) {
        enqueue(e, c.cost, c.position, false);
        continue;
      }
      try_collapse(e, key, c.position, false, &in);
    } else {
      try_collapse(e, key, p.target, p.retried);
    }
  }
  // Storage freed by the collapses is reclaimed here too, not only after a dumping: the tandem
  // without dumping would otherwise hold as much as brute force.
  maybe_collect_garbage();
}

void WorkingSurface::Engine::try_collapse(EH e, double cost, const detail::Vec3& target, bool retried,
                                          const CostInputs* known) {
  const HH h = mesh_->halfedge_handle(e, 0);
  if (!detail::link_condition_ok(*mesh_, h, marks_)) {
    ++counters_.rejected_link;
    return;
  }
  // The distance bound first: it refuses many more candidates than the shape test (2 in 3 pops on
  // noisy surfaces, against 1 in 25), so the shape test mostly runs for collapses that happen.
  bool gathered = false; // the patch around h is read once for every position tried
  const double error = collapse_error(h, target, gathered);
  if (!(error <= options_.max_error)) {
    // Retried at the simple positions as after a flip. (Without the retry: 4 % more triangles and
    // a quarter less time on noisy surfaces, but worse seams between blocks.)
    ++counters_.rejected_distance;
  } else if (!detail::collapse_keeps_shape(*mesh_, h, target, points_)) {
    ++counters_.rejected_flip;
  } else {
    collapse(h, target, cost, error);
    return;
  }
  if (retried) return;
  // One more chance at the simple positions (volume-preserving when asked) that keep every
  // triangle's shape.
  CostInputs read;
  if (!known && !costs_.inputs(h, read)) return;
  const CostInputs& in = known ? *known : read;
  const detail::AttaliCost& attali = costs_.attali();
  const auto prepared = attali.prepare(in);
  Vec3 positions[3];
  const int count = attali.fallback_positions(prepared, positions);
  Candidate options[3];
  for (int k = 0; k < count; ++k)
    options[k] = attali.at(prepared, positions[k]);
  for (int k = 1; k < count; ++k) // by cost (at most three)
    for (int j = k; j > 0 && options[j].cost < options[j - 1].cost; --j)
      std::swap(options[j], options[j - 1]);
  for (int k = 0; k < count; ++k) {
    const Candidate& o = options[k];
    if (!(o.shape_error <= options_.max_error)) continue;
    if (!(collapse_error(h, o.position, gathered) <= options_.max_error)) continue;
    if (!detail::collapse_keeps_shape(*mesh_, h, o.position, points_)) continue;
    ++counters_.retried;
    enqueue(e, o.cost, o.position, true);
    return;
  }
}

double WorkingSurface::Engine::collapse_error(HH h, const Vec3& target, bool& gathered) {
  if (!options_.guarantee_distance) return 0.0;
  if (!gathered) distance_.gather(*mesh_, h, points_, vrec_);
  gathered = true;
  return distance_.bound(target, options_.max_error);
}

void WorkingSurface::Engine::report_collapse(HH h, const Vec3& target, double cost, double error) {
  const EdgeGeometry g = geometry_of(h);
  CollapseEvent ev;
  ev.a = g.a;
  ev.b = g.b;
  ev.c = target;
  ev.height = g.height();
  ev.rad = g.rad();
  ev.reach = g.reach();
  ev.front = front_;
  ev.open_face_distance = region_.distance_to_open_faces(g.midpoint());
  ev.cost = cost;
  ev.distance_bound = error;
  CostInputs in;
  if (costs_.inputs(h, in)) ev.shape_error = costs_.attali().at(costs_.attali().prepare(in), target).shape_error;
  // The invariants of the time lag and the extended time lag, checked on every collapse in debug.
  assert(front_rule_->key(g) < front_);
  assert(!options_.time_lag || ev.reach < ev.front);
  assert(!options_.extended_time_lag || ev.open_face_distance > ev.rad);
  assert(options_.extended_time_lag || (!region_.on_open_face(g.a) && !region_.on_open_face(g.b)));
  assert(ev.shape_error <= options_.max_error);
  assert(ev.distance_bound <= options_.max_error);
  if (observer_) observer_->on_collapse(ev);
}

void WorkingSurface::Engine::collapse(HH h, const Vec3& target, double cost, double error) {
#ifdef NDEBUG
  if (observer_) report_collapse(h, target, cost, error);
#else
  report_collapse(h, target, cost, error);
#endif
  const VH a = mesh_->from_vertex_handle(h), b = mesh_->to_vertex_handle(h);
  const EdgeGeometry g = geometry_of(h);

  // The three edges that disappear leave the queues (ab, bx and ay: collapse_halfedge keeps ax
  // and by); the others are re-placed once c is known.
  {
    const HH o = mesh_->opposite_halfedge_handle(h);
    EH doomed[3] = {mesh_->edge_handle(h), EH(), EH()};
    if (mesh_->face_handle(h).is_valid()) doomed[1] = mesh_->edge_handle(mesh_->next_halfedge_handle(h));
    if (mesh_->face_handle(o).is_valid()) doomed[2] = mesh_->edge_handle(mesh_->next_halfedge_handle(o));
    for (EH e : doomed)
      if (e.is_valid() && erec(e).state != EdgeState::idle) set_state(e, EdgeState::idle, 0.0);
  }
  // The terms of the triangles around a and b leave their other corners' sums: every one of these
  // triangles changes or disappears. Each triangle once: those around a, then those around b that
  // do not contain a.
  for (VH v : {a, b}) {
    const HH start = mesh_->halfedge_handle(v);
    HH s = start;
    do {
      const FH f = mesh_->face_handle(s);
      if (f.is_valid()) {
        const VH p = mesh_->to_vertex_handle(s), q = mesh_->to_vertex_handle(mesh_->next_halfedge_handle(s));
        if (!(v == b && (p == a || q == a))) costs_.remove_face_terms(f, a, b);
      }
      s = detail::next_outgoing(*mesh_, s);
    } while (s != start);
  }

  // Component bookkeeping: a's component keeps b as a member if it used a.
  detail::VertexRecord& ra = vrec(a);
  detail::VertexRecord& rb = vrec(b);
  {
    detail::ComponentRecord& comp = components_.at(components_.find(ra.component));
    if (comp.member == a.idx()) comp.member = b.idx();
  }

  const detail::CollapseResult result = detail::collapse_halfedge(*mesh_, h); // a, its edges and faces die
  live_faces_ -= static_cast<std::size_t>(result.removed_face_count);
  --live_vertices_;

  rb.shape += ra.shape;
  rb.height = g.height();
  rb.rad = g.rad();
  rb.tolerance = error;
  rb.lattice_id = detail::kNoLatticeId;
  rb.border |= ra.border;
  points_[b.idx()] = detail::HalfedgeMesh::Point(target[0], target[1], target[2]);

  // New terms of the triangles around c.
  rb.isotropy = detail::Isotropy{};
  rb.cross_sum = {0.0, 0.0, 0.0};
  rb.link_sum = {0.0, 0.0, 0.0};
  const HH start = mesh_->halfedge_handle(b);
  HH s = start;
  do {
    const FH f = mesh_->face_handle(s);
    if (f.is_valid()) costs_.add_face_terms(f);
    s = detail::next_outgoing(*mesh_, s);
  } while (s != start);

  ++counters_.collapses;
  ++rb.version;
  s = start;
  do {
    ++vrec(mesh_->to_vertex_handle(s)).version;
    s = detail::next_outgoing(*mesh_, s);
  } while (s != start);
  s = start;
  do {
    place(mesh_->edge_handle(s));
    s = detail::next_outgoing(*mesh_, s);
  } while (s != start);
}

} // namespace geotandem::tandem
