#include "collapse_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace geotandem::tandem::detail {

namespace {
inline double cross2(double ux, double uy, double vx, double vy) {
  return ux * vy - uy * vx;
}
} // namespace

double CollapseDistance::simplicial(const Vec3& a, double da, const Vec3& b, double db, const Vec3& c) {
  return std::max(da + norm(a - c), db + norm(b - c));
}

void CollapseDistance::gather(const HalfedgeMesh& mesh, HH h, const HalfedgeMesh::Point* points,
                              const VertexRecord* records) {
  const VH a = mesh.from_vertex_handle(h), b = mesh.to_vertex_handle(h);
  const Vec3 pa = to_vec(points[a.idx()]), pb = to_vec(points[b.idx()]);
  const double da = records[a.idx()].tolerance, db = records[b.idx()].tolerance;
  a_ = pa;
  b_ = pb;
  da_ = da;
  db_ = db;
  boundary_ = mesh.is_boundary(a) || mesh.is_boundary(b);
  n_points_ = n_old_ = n_new_ = n_edges_ = 0;
  if (boundary_) return;
  // a and b are interior, so both triangles of ab exist; x and y, opposite ab, are their only
  // common neighbours (the link condition was checked).
  const VH x = mesh.to_vertex_handle(mesh.next_halfedge_handle(h));
  const VH y = mesh.to_vertex_handle(mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(h)));
  // The two rings, as vertices in rotation order; the triangle at step i is (v, p_i, p_(i-1)).
  std::size_t ring_end[2];
  std::size_t n_ring = 0;
  for (const VH v : {a, b}) {
    const HH start = mesh.halfedge_handle(v);
    HH s = start;
    do {
      grow(ring_, n_ring + 1);
      ring_[n_ring++] = mesh.to_vertex_handle(s);
      s = next_outgoing(mesh, s);
    } while (s != start);
    ring_end[v == a ? 0 : 1] = n_ring;
  }
  // Every array below holds at most one entry per ring step (points three more): room once.
  grow(points_, n_ring + 3);
  grow(tolerances_, n_ring + 3);
  grow(local_, n_ring);
  grow(old_triangles_, n_ring);
  grow(new_triangles_, n_ring);
  grow(old_edges_, n_ring);
  grow(fan_next_, n_ring + 3);
  grow(hits_, n_ring + 4); // projected(): up to one per point, and one more
  points_[0] = pa;
  points_[1] = pb;
  points_[2] = pa; // c's entry, framed as a's: its share of the scale below is a's
  tolerances_[0] = da;
  tolerances_[1] = db;
  tolerances_[2] = 0.0;
  n_points_ = 3;
  const auto add = [&](VH p) { // a new local number
    points_[n_points_] = to_vec(points[p.idx()]);
    tolerances_[n_points_] = records[p.idx()].tolerance;
    return static_cast<int>(n_points_++);
  };
  int ix = -1, iy = -1; // x and y are in both rings: numbered once
  for (std::size_t k = 0; k < n_ring; ++k) {
    const VH p = ring_[k];
    local_[k] = p == a   ? 0
                : p == b ? 1
                : p == x ? (ix < 0 ? ix = add(p) : ix)
                : p == y ? (iy < 0 ? iy = add(p) : iy)
                         : add(p);
  }
  for (int iv = 0; iv < 2; ++iv) {
    const std::size_t first = iv == 0 ? 0 : ring_end[0], last = ring_end[iv];
    for (std::size_t k = first; k < last; ++k) {
      const int ip = local_[k], iq = local_[k == first ? last - 1 : k - 1];
      if (iv == 0 || (ip != 0 && iq != 0)) { // each triangle once
        old_triangles_[n_old_++] = {iv, ip, iq};
        if (ip > 1 && iq > 1) new_triangles_[n_new_++] = {2, ip, iq}; // abx and aby vanish
      }
      if (ip > 1)
        old_edges_[n_edges_++] = {iv, ip};
      else if (iv == 0)
        old_edges_[n_edges_++] = {0, 1};
    }
  }
  // The link in counter-clockwise order around c (seen from the side the patch faces): each new
  // triangle (c, p, q) is one step p -> q of it.
  std::fill_n(fan_next_.begin(), n_points_, -1);
  for (std::size_t i = 0; i < n_new_; ++i)
    fan_next_[static_cast<std::size_t>(new_triangles_[i][1])] = new_triangles_[i][2];
  // The vector area of the patch (the same before and after: it depends on the boundary only; c
  // is not in the old triangles) and the frame of the projection.
  Vec3 n{0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < n_old_; ++i) {
    const auto& t = old_triangles_[i];
    n = n + cross(points_[static_cast<std::size_t>(t[1])] - points_[static_cast<std::size_t>(t[0])],
                  points_[static_cast<std::size_t>(t[2])] - points_[static_cast<std::size_t>(t[0])]);
  }
  area_length_ = norm(n);
  if (!(area_length_ > 0.0)) return; // projected() gives up
  n_ = (1.0 / area_length_) * n;
  Vec3 u = std::fabs(n_[0]) < 0.6 ? cross(n_, Vec3{1.0, 0.0, 0.0}) : cross(n_, Vec3{0.0, 1.0, 0.0});
  u_ = (1.0 / norm(u)) * u;
  v_ = cross(n_, u_);
  // The patch in the frame, from a: each position tried then only shifts it by its own image
  // (the frame does not depend on c).
  grow(framed_, n_points_);
  grow(projected_, n_points_);
  for (std::size_t i = 0; i < n_points_; ++i) {
    const Vec3 d = points_[i] - pa;
    framed_[i] = {dot(d, u_), dot(d, v_), dot(d, n_)};
  }
}

double CollapseDistance::bound(const Vec3& c, double limit) {
  const double simple = simplicial(a_, da_, b_, db_, c);
  if (boundary_) return simple;
  const double d = projected(c, std::min(simple, limit));
  return d >= 0.0 && d < simple ? d : simple;
}

double CollapseDistance::projected(const Vec3& c, double limit) {
  // The patch seen from c: its image in the frame (from a) shifted by c's. The frame is
  // orthonormal, so the largest squared distance to c (the scale of the tolerances below) is
  // read there too.
  if (!(area_length_ > 0.0)) return -1.0; // also: the patch was not framed
  const Vec3 dc = c - a_;
  const Point2 origin{dot(dc, u_), dot(dc, v_), dot(dc, n_)};
  double scale2 = 0.0;
  for (std::size_t i = 0; i < n_points_; ++i) {
    const Point2 q{framed_[i].u - origin.u, framed_[i].v - origin.v, framed_[i].z - origin.z};
    projected_[i] = q;
    scale2 = std::max(scale2, q.u * q.u + q.v * q.v + q.z * q.z);
  }
  projected_[2] = Point2{};
  if (!(area_length_ > 1e-9 * scale2)) return -1.0;
  const auto at = [this](int i) -> const Point2& { return projected_[static_cast<std::size_t>(i)]; };

  // Whether a triangle holds a point, from its doubled area and the point's two cross products
  // (s1 / area and s2 / area are the weights of the second and third corners, set in w).
  const auto holds = [](double area, double s1, double s2, double w[3]) {
    // Clearly outside (a weight below twice the slack) without dividing: most triangles tried.
    constexpr double slack = -1e-9;
    const double margin = -2.0 * slack * std::fabs(area);
    if ((area > 0.0 && (s1 < -margin || s2 < -margin)) || (area < 0.0 && (s1 > margin || s2 > margin))) return false;
    w[1] = s1 / area;
    w[2] = s2 / area;
    w[0] = 1.0 - w[1] - w[2];
    return w[0] >= slack && w[1] >= slack && w[2] >= slack;
  };
  // The triangle of the old patch that holds a point, and the point's barycentric weights.
  const auto locate_in_old = [&](const Point2& x, double w[3]) {
    for (std::size_t i = 0; i < n_old_; ++i) {
      const auto& t = old_triangles_[i];
      const Point2 &p = at(t[0]), &q = at(t[1]), &r = at(t[2]);
      const double area = cross2(q.u - p.u, q.v - p.v, r.u - p.u, r.v - p.v);
      const double s1 = cross2(x.u - p.u, x.v - p.v, r.u - p.u, r.v - p.v);
      const double s2 = cross2(q.u - p.u, q.v - p.v, x.u - p.u, x.v - p.v);
      if (holds(area, s1, s2, w)) return &t;
    }
    return static_cast<const std::array<int, 3>*>(nullptr);
  };
  // The same in the new patch, the fan around c: its triangles start at c, the origin, and
  // subtracting it would change no bit.
  const auto locate_in_fan = [&](const Point2& x, double w[3]) {
    for (std::size_t i = 0; i < n_new_; ++i) {
      const auto& t = new_triangles_[i];
      const Point2 &q = at(t[1]), &r = at(t[2]);
      if (holds(cross2(q.u, q.v, r.u, r.v), cross2(x.u, x.v, r.u, r.v), cross2(q.u, q.v, x.u, x.v), w)) return &t;
    }
    return static_cast<const std::array<int, 3>*>(nullptr);
  };
  const auto tol = [this](int i) { return tolerances_[static_cast<std::size_t>(i)]; };
  // Each overlay vertex x asks w_c(x) d_c >= tol_old(x) + |D(x)| - (the new tolerance's other terms).
  double need = 0.0;
  // Fails (the projection map is of no use) once d_c would exceed the limit.
  const auto require = [&need, limit](double wc, double rhs) {
    if (rhs <= 0.0) return true;
    if (!(wc > 1e-9)) return false;
    need = std::max(need, rhs / wc);
    return need <= limit;
  };
  // a and b first: on a refused collapse it is usually there that d_c passes the limit, and every
  // way out below gives the same answer (no use of the projection), so their order is free.
  double w[3];
  // The sectors of the fan around c that hold a and b, each named by the link vertex on its
  // clockwise side.
  int sector[2];
  for (int i = 0; i < 2; ++i) { // a and b, in the new patch (c is its triangles' first corner)
    const auto* t = locate_in_fan(at(i), w);
    if (!t) return -1.0;
    sector[i] = (*t)[1];
    const double z = w[0] * at(2).z + w[1] * at((*t)[1]).z + w[2] * at((*t)[2]).z;
    if (!require(w[0], tol(i) + std::fabs(z - at(i).z) - w[1] * tol((*t)[1]) - w[2] * tol((*t)[2]))) return -1.0;
  }
  // One to one: every triangle of both patches keeps its orientation, and the fan around c turns
  // once (its boundary, the patch's, is then a simple polygon).
  const double tiny = 1e-12 * scale2;
  const auto positive = [&](const std::array<int, 3>& t) {
    const Point2 &p = at(t[0]), &q = at(t[1]), &r = at(t[2]);
    return cross2(q.u - p.u, q.v - p.v, r.u - p.u, r.v - p.v) > tiny;
  };
  for (std::size_t i = 0; i < n_old_; ++i)
    if (!positive(old_triangles_[i])) return -1.0;
  // With every sector (c, p, q) turning by less than pi, the fan's winding number is how many of
  // them hold the direction (1, 0) (half-open, so that one on a ray counts once).
  int winding = 0;
  for (std::size_t i = 0; i < n_new_; ++i) {
    const auto& t = new_triangles_[i];
    if (!positive(t)) return -1.0;
    const Point2 &p = at(t[1]), &q = at(t[2]);
    if (-p.v >= 0.0 && q.v > 0.0) ++winding; // cross2(p, (1, 0)) >= 0 and cross2((1, 0), q) > 0
  }
  if (winding != 1) return -1.0;

  { // c, in the old patch
    const auto* t = locate_in_old(at(2), w);
    if (!t) return -1.0;
    double z = 0.0, old = 0.0;
    for (int k = 0; k < 3; ++k) {
      z += w[k] * at((*t)[static_cast<std::size_t>(k)]).z;
      old += w[k] * tol((*t)[static_cast<std::size_t>(k)]);
    }
    if (!require(1.0, old + std::fabs(z - at(2).z))) return -1.0;
  }
  // Crossings of the old interior edges (at a or b) with the new ones (c x): c is the origin. The
  // new edge c x can only cross the old edge p q (p is a or b) when x's direction lies in the wedge
  // that p q spans seen from c, under pi; the fan being one turn in order, those x are a run of
  // the link from the sector holding p to q (or to the sector holding b). Both ends of the run are
  // taken with their sectors' sides, and the crossings are then computed exactly; p q nearly in
  // line with c tries every x.
  const int n_points = static_cast<int>(n_points_);
  for (std::size_t i = 0; i < n_edges_; ++i) {
    const auto& e = old_edges_[i];
    const Point2 &p = at(e[0]), &q = at(e[1]);
    const double du = q.u - p.u, dv = q.v - p.v;
    const double turn = cross2(p.u, p.v, q.u, q.v);
    int count = 0;
    bool walked = false;
    if (std::fabs(turn) > 1e-6 * (p.u * p.u + p.v * p.v + q.u * q.u + q.v * q.v)) {
      const int p_cw = sector[e[0]], p_ccw = fan_next_[static_cast<std::size_t>(p_cw)];
      const int q_cw = e[1] > 1 ? e[1] : sector[1];
      const int q_ccw = e[1] > 1 ? e[1] : fan_next_[static_cast<std::size_t>(q_cw)];
      const int last = turn > 0.0 ? q_ccw : p_ccw;
      for (int x = turn > 0.0 ? p_cw : q_cw; x > 1 && count < n_points; x = fan_next_[static_cast<std::size_t>(x)]) {
        if (x != e[1]) hits_[static_cast<std::size_t>(count++)] = x;
        if (x == last) {
          walked = true;
          break;
        }
      }
    }
    if (!walked) { // in line with c (or a fan that is not one turn, which the tests above rule out)
      count = 0;
      for (int x = 3; x < n_points; ++x)
        if (x != e[1]) hits_[static_cast<std::size_t>(count++)] = x;
    }
    for (int k = 0; k < count; ++k) {
      const int x = hits_[static_cast<std::size_t>(k)];
      const Point2& r = at(x);
      const double denom = cross2(r.u, r.v, du, dv);
      if (std::fabs(denom) <= tiny) continue;              // parallel: the extremes are at the end points
      const double t = cross2(p.u, p.v, du, dv) / denom;   // along c -> x
      const double s = cross2(p.u, p.v, r.u, r.v) / denom; // along p -> q
      if (t < 0.0 || t > 1.0 || s < 0.0 || s > 1.0) continue;
      const double z_new = at(2).z + t * (r.z - at(2).z);
      const double z_old = p.z + s * (q.z - p.z);
      const double old = (1.0 - s) * tol(e[0]) + s * tol(e[1]);
      if (!require(1.0 - t, old + std::fabs(z_new - z_old) - t * tol(x))) return -1.0;
    }
  }
  // Rounding: the bound must not be below the exact one.
  return need * (1.0 + 1e-9) + 1e-12 * std::sqrt(scale2);
}

} // namespace geotandem::tandem::detail
