#include "collapser.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "geotandem/core/error.hpp"

namespace geotandem::tandem::detail {

namespace {

// The open face of `after` that still holds back a parked edge whose record names a face of
// `before` and a square of it, or -1 when none does or either is not known. `kept`:
// before.open_faces_kept_in(after).
int face_after_merge(const EdgeRecord& r, const std::vector<int>& kept, const Region& before, const Region& after) {
  if (r.face == kUnknownFace || r.face >= kept.size()) return -1;
  if (kept[r.face] >= 0 || r.pending_or_square == kUnknownSquare) return kept[r.face];
  OpenFace square = before.open_faces()[r.face];
  square.lo = square_corner(r.pending_or_square);
  square.hi = {square.lo[0] + 1.0, square.lo[1] + 1.0};
  return after.open_face_holding(square);
}

} // namespace

Collapser::Collapser(SurfaceStorage& storage, const Region& region, int axis, const SimplifyOptions& options,
                     const std::array<double, 3>& cube_hi, CollapseObserver* observer)
    : storage_(storage), mesh_(storage.mesh()), region_(region), options_(options),
      front_rule_(make_front_rule(options.time_lag, axis)), face_rule_(make_face_rule(options.extended_time_lag)),
      costs_(storage.mesh(), options, cube_hi), observer_(observer) {
  grown();
}

EdgeGeometry Collapser::geometry_of(HH h) const {
  const VH a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
  const VertexRecord& ra = vrec(a);
  const VertexRecord& rb = vrec(b);
  EdgeGeometry g;
  g.a = storage_.position(a);
  g.b = storage_.position(b);
  g.height_a = ra.height;
  g.height_b = rb.height;
  g.rad_a = ra.rad;
  g.rad_b = rb.rad;
  return g;
}

void Collapser::set_state(EH e, EdgeState state, double key, const Region::NearestFace* hold) {
  if (queues_.move(erec(e), static_cast<std::int32_t>(e.idx()), state, key, hold)) {
    const VH a = mesh_.to_vertex_handle(mesh_.halfedge_handle(e, 0));
    storage_.components().add_waiting(vrec(a).component, waiting(state) ? 1 : -1);
  }
}

void Collapser::enqueue(EH e, double cost, const Vec3& target, bool retried) {
  set_state(e, EdgeState::candidate, cost);
  Pending& p = pending(e);
  p.target = target;
  p.stamp = stamp_of(e);
  p.retried = retried;
  p.dirty = false;
}

std::uint32_t Collapser::stamp_of(EH e) const {
  const HH h = mesh_.halfedge_handle(e, 0);
  return vrec(mesh_.from_vertex_handle(h)).version + vrec(mesh_.to_vertex_handle(h)).version;
}

void Collapser::place(EH e) {
  const HH h = mesh_.halfedge_handle(e, 0);
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

void Collapser::activate(double front) {
  if (front < front_)
    throw InvalidArgument("working surface: the front cannot move back from " + std::to_string(front_) + " to " +
                          std::to_string(front));
  front_ = front;
  std::vector<std::int32_t> bucket;
  while (queues_.delayed_below(front_, bucket)) {
    bool moved = false;
    for (std::int32_t e : bucket) {
      if (!(erec(EH(e)).key < front_)) continue;
      place(EH(e));
      moved = true;
    }
    if (!moved) break; // the lowest bucket only holds keys at or above the front
  }
}

void Collapser::simplify(const CancelToken* cancel) {
  std::uint32_t steps = 0;
  while (queues_.has_candidates()) {
    if (cancel && (++steps & 0xFFFu) == 0) cancel->throw_if_cancelled();
    const EH e(queues_.cheapest().item);
    const double key = queues_.cheapest().key;
    const Pending p = pending(e); // a copy: leaving Q frees its place
    set_state(e, EdgeState::idle, 0.0);
    if (p.dirty || p.stamp != stamp_of(e)) {
      // Collapses nearby changed what its cost depends on: compute it again, and put it back
      // when it became dearer.
      Candidate c;
      CostInputs in;
      if (!costs_.evaluate(mesh_.halfedge_handle(e, 0), c, counters_, in)) continue;
      if (c.cost > key + 1e-12 * (1.0 + key)) {
        enqueue(e, c.cost, c.position, false);
        continue;
      }
      try_collapse(e, key, c.position, false, &in);
    } else {
      try_collapse(e, key, p.target, p.retried);
    }
  }
}

void Collapser::try_collapse(EH e, double cost, const Vec3& target, bool retried, const CostInputs* known) {
  const HH h = mesh_.halfedge_handle(e, 0);
  if (!link_condition_ok(mesh_, h, marks_)) {
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
  } else if (!collapse_keeps_shape(mesh_, h, target, mesh_.points())) {
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
  const AttaliCost& attali = costs_.attali();
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
    if (!collapse_keeps_shape(mesh_, h, o.position, mesh_.points())) continue;
    ++counters_.retried;
    enqueue(e, o.cost, o.position, true);
    return;
  }
}

double Collapser::collapse_error(HH h, const Vec3& target, bool& gathered) {
  if (!options_.guarantee_distance) return 0.0;
  if (!gathered) distance_.gather(mesh_, h, mesh_.points(), mesh_.vertex_records());
  gathered = true;
  return distance_.bound(target, options_.max_error);
}

void Collapser::report_collapse(HH h, const Vec3& target, double cost, double error) {
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

void Collapser::collapse(HH h, const Vec3& target, double cost, double error) {
#ifdef NDEBUG
  if (observer_) report_collapse(h, target, cost, error);
#else
  report_collapse(h, target, cost, error);
#endif
  const VH a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
  const EdgeGeometry g = geometry_of(h);

  // The three edges that disappear leave the queues (ab, bx and ay: collapse_halfedge keeps ax
  // and by); the others are re-placed once c is known.
  {
    const HH o = mesh_.opposite_halfedge_handle(h);
    EH doomed[3] = {mesh_.edge_handle(h), EH(), EH()};
    if (mesh_.face_handle(h).is_valid()) doomed[1] = mesh_.edge_handle(mesh_.next_halfedge_handle(h));
    if (mesh_.face_handle(o).is_valid()) doomed[2] = mesh_.edge_handle(mesh_.next_halfedge_handle(o));
    for (EH e : doomed)
      if (e.is_valid() && erec(e).state != EdgeState::idle) set_state(e, EdgeState::idle, 0.0);
  }
  // The terms of the triangles around a and b leave their other corners' sums: every one of these
  // triangles changes or disappears. Each triangle once: those around a, then those around b that
  // do not contain a.
  for (VH v : {a, b}) {
    const HH start = mesh_.halfedge_handle(v);
    HH s = start;
    do {
      const FH f = mesh_.face_handle(s);
      if (f.is_valid()) {
        const VH p = mesh_.to_vertex_handle(s), q = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(s));
        if (!(v == b && (p == a || q == a))) costs_.remove_face_terms(f, a, b);
      }
      s = next_outgoing(mesh_, s);
    } while (s != start);
  }

  // Component bookkeeping: a's component keeps b as a member if it used a.
  VertexRecord& ra = vrec(a);
  VertexRecord& rb = vrec(b);
  {
    ComponentRecord& comp = storage_.components().at(storage_.components().find(ra.component));
    if (comp.member == a.idx()) comp.member = b.idx();
  }

  const CollapseResult result = collapse_halfedge(mesh_, h); // a, its edges and faces die
  storage_.forget(1, static_cast<std::size_t>(result.removed_face_count));

  rb.shape += ra.shape;
  rb.height = g.height();
  rb.rad = g.rad();
  rb.tolerance = error;
  rb.lattice_id = kNoLatticeId;
  rb.border |= ra.border;
  storage_.set_position(b, target);

  // New terms of the triangles around c.
  rb.isotropy = Isotropy{};
  rb.cross_sum = {0.0, 0.0, 0.0};
  rb.link_sum = {0.0, 0.0, 0.0};
  const HH start = mesh_.halfedge_handle(b);
  HH s = start;
  do {
    const FH f = mesh_.face_handle(s);
    if (f.is_valid()) costs_.add_face_terms(f);
    s = next_outgoing(mesh_, s);
  } while (s != start);

  ++counters_.collapses;
  ++rb.version;
  s = start;
  do {
    ++vrec(mesh_.to_vertex_handle(s)).version;
    s = next_outgoing(mesh_, s);
  } while (s != start);
  s = start;
  do {
    place(mesh_.edge_handle(s));
    s = next_outgoing(mesh_, s);
  } while (s != start);
}

void Collapser::place_parked_again(const Region& before) {
  // A parked edge's ball reaches the face its record names, at a point in the square it names.
  // When the grown region still has that square open (inside one of its open faces: the whole
  // face when it is kept, the usual case), the ball still reaches an open face and placing the
  // edge again would only park it again with the same key: it is skipped, and its face
  // renumbered. The others (and those not known: the other side's) are placed again in list
  // order, as placing every parked edge would (the same queues, to the bit).
  const std::vector<int> kept = before.open_faces_kept_in(region_);
  std::vector<std::int32_t> again;
  for (std::int32_t e : queues_.parked()) {
    EdgeRecord& r = erec(EH(e));
    const int face = face_after_merge(r, kept, before, region_);
    if (face >= 0 && face < kUnknownFace) {
      r.face = static_cast<std::uint16_t>(face);
    } else {
      r.face = kUnknownFace;
      again.push_back(e);
    }
  }
  for (std::int32_t e : again)
    place(EH(e));
}

void Collapser::find_parked_faces() {
  for (std::int32_t e : queues_.parked()) {
    EdgeRecord& r = erec(EH(e));
    if (r.face != kUnknownFace) continue;
    const Region::NearestFace hold = face_rule_->holding_face(geometry_of(mesh_.halfedge_handle(EH(e), 0)), region_);
    EdgeQueues::hold_at(r, &hold);
  }
}

void Collapser::restore_edge(VH a, VH b, const StateEdge& edge, std::size_t index) {
  const HH h = a != b ? find_halfedge(mesh_, a, b) : HH();
  if (!h.is_valid())
    throw DataError("working surface state: edge " + std::to_string(index) + " (" + std::to_string(a.idx()) + ", " +
                    std::to_string(b.idx()) + ") is not an edge of the surface");
  const EdgeState state = edge.state;
  if (state != EdgeState::idle && state != EdgeState::candidate && state != EdgeState::delayed &&
      state != EdgeState::parked)
    throw DataError("working surface state: edge " + std::to_string(index) + " has an unknown state");
  const EH e = mesh_.edge_handle(h);
  if (erec(e).state != EdgeState::idle) set_state(e, EdgeState::idle, 0.0);
  set_state(e, state, edge.key);
  if (state == EdgeState::candidate) pending(e) = edge.pending;
}

void Collapser::renumbered(bool give_back) {
  marks_.clear();
  grown();
  costs_.recompute_face_terms();
  queues_.rebuild(mesh_.edge_records(), mesh_.n_edges(), give_back);
  ++counters_.garbage_collections;
}

void Collapser::delay_new_faces(const std::vector<FH>& faces) {
  for (FH f : faces)
    costs_.add_face_terms(f);
  for (FH f : faces) {
    HH h = mesh_.halfedge_handle(f);
    for (int k = 0; k < 3; ++k, h = mesh_.next_halfedge_handle(h)) {
      const EH e = mesh_.edge_handle(h);
      if (erec(e).state == EdgeState::delayed) continue; // both of its triangles are new: already done
      set_state(e, EdgeState::delayed, front_rule_->key(geometry_of(mesh_.halfedge_handle(e, 0))));
    }
  }
}

void Collapser::add_faces(const std::vector<FH>& faces) {
  for (FH f : faces)
    costs_.add_face_terms(f);
}

void Collapser::place_parked() {
  const std::vector<std::int32_t> parked = queues_.parked();
  for (std::int32_t e : parked)
    place(EH(e));
}

} // namespace geotandem::tandem::detail
