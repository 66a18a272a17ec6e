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

int CollapseDistance::add(VH v, const HalfedgeMesh::Point* points, const VertexRecord* records) {
  points_.push_back(to_vec(points[v.idx()]));
  tolerances_.push_back(records[v.idx()].tolerance);
  return static_cast<int>(points_.size() - 1);
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
  if (boundary_) return;
  // a and b are interior, so both triangles of ab exist; x and y, opposite ab, are their only
  // common neighbours (the link condition was checked).
  const VH x = mesh.to_vertex_handle(mesh.next_halfedge_handle(h));
  const VH y = mesh.to_vertex_handle(mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(h)));
  points_.assign({pa, pb, Vec3{}}); // c goes in its place in bound()
  tolerances_.assign({da, db, 0.0});
  old_triangles_.clear();
  new_triangles_.clear();
  old_edges_.clear();
  int ix = -1, iy = -1;
  for (const VH v : {a, b}) {
    const int iv = v == a ? 0 : 1;
    // The neighbours in rotation order; the triangle at step i is (v, p_i, p_(i-1)).
    ring_.clear();
    const HH start = mesh.halfedge_handle(v);
    HH s = start;
    do {
      const VH p = mesh.to_vertex_handle(s);
      int ip;
      if (p == a) {
        ip = 0;
      } else if (p == b) {
        ip = 1;
      } else if (p == x) {
        ip = ix < 0 ? (ix = add(p, points, records)) : ix;
      } else if (p == y) {
        ip = iy < 0 ? (iy = add(p, points, records)) : iy;
      } else {
        ip = add(p, points, records);
      }
      ring_.push_back(ip);
      s = next_outgoing(mesh, s);
    } while (s != start);
    for (std::size_t k = 0; k < ring_.size(); ++k) {
      const int ip = ring_[k], iq = ring_[k == 0 ? ring_.size() - 1 : k - 1];
      if (iv == 0 || (ip != 0 && iq != 0)) { // each triangle once
        old_triangles_.push_back({iv, ip, iq});
        if (ip > 1 && iq > 1) new_triangles_.push_back({2, ip, iq}); // abx and aby vanish
      }
      if (ip > 1)
        old_edges_.push_back({iv, ip});
      else if (iv == 0)
        old_edges_.push_back({0, 1});
    }
  }
  // The link in counter-clockwise order around c (seen from the side the patch faces): each new
  // triangle (c, p, q) is one step p -> q of it.
  fan_next_.assign(points_.size(), -1);
  for (const auto& t : new_triangles_)
    fan_next_[static_cast<std::size_t>(t[1])] = t[2];
  // The vector area of the patch (the same before and after: it depends on the boundary only; c
  // is not in the old triangles) and the frame of the projection.
  Vec3 n{0.0, 0.0, 0.0};
  for (const auto& t : old_triangles_)
    n = n + cross(points_[static_cast<std::size_t>(t[1])] - points_[static_cast<std::size_t>(t[0])],
                  points_[static_cast<std::size_t>(t[2])] - points_[static_cast<std::size_t>(t[0])]);
  area_length_ = norm(n);
  if (!(area_length_ > 0.0)) return;
  n_ = (1.0 / area_length_) * n;
  Vec3 u = std::fabs(n_[0]) < 0.6 ? cross(n_, Vec3{1.0, 0.0, 0.0}) : cross(n_, Vec3{0.0, 1.0, 0.0});
  u_ = (1.0 / norm(u)) * u;
  v_ = cross(n_, u_);
}

double CollapseDistance::bound(const Vec3& c, double limit) {
  const double simple = simplicial(a_, da_, b_, db_, c);
  if (boundary_) return simple;
  points_[2] = c;
  const double d = projected(c, std::min(simple, limit));
  return d >= 0.0 && d < simple ? d : simple;
}

double CollapseDistance::projected(const Vec3& c, double limit) {
  double scale2 = 0.0;
  for (const Vec3& p : points_)
    scale2 = std::max(scale2, norm2(p - c));
  if (!(area_length_ > 1e-9 * scale2)) return -1.0;
  const Vec3 &u = u_, &v = v_, &n = n_;
  projected_.resize(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Vec3 d = points_[i] - c;
    projected_[i] = {dot(d, u), dot(d, v), dot(d, n)};
  }
  const auto at = [this](int i) -> const Point2& { return projected_[static_cast<std::size_t>(i)]; };

  // The triangle of a triangulation that holds a point, and the point's barycentric weights.
  const auto locate = [&](const std::vector<std::array<int, 3>>& triangles, const Point2& x, double w[3]) {
    for (const auto& t : triangles) {
      const Point2 &p = at(t[0]), &q = at(t[1]), &r = at(t[2]);
      const double area = cross2(q.u - p.u, q.v - p.v, r.u - p.u, r.v - p.v);
      const double s1 = cross2(x.u - p.u, x.v - p.v, r.u - p.u, r.v - p.v);
      const double s2 = cross2(q.u - p.u, q.v - p.v, x.u - p.u, x.v - p.v);
      // Clearly outside (a weight below twice the slack) without dividing: most triangles tried.
      constexpr double slack = -1e-9;
      const double margin = -2.0 * slack * std::fabs(area);
      if ((area > 0.0 && (s1 < -margin || s2 < -margin)) || (area < 0.0 && (s1 > margin || s2 > margin))) continue;
      w[1] = s1 / area;
      w[2] = s2 / area;
      w[0] = 1.0 - w[1] - w[2];
      if (w[0] >= slack && w[1] >= slack && w[2] >= slack) return &t;
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
    const auto* t = locate(new_triangles_, at(i), w);
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
  for (const auto& t : old_triangles_)
    if (!positive(t)) return -1.0;
  // With every sector (c, p, q) turning by less than pi, the fan's winding number is how many of
  // them hold the direction (1, 0) (half-open, so that one on a ray counts once).
  int winding = 0;
  for (const auto& t : new_triangles_) {
    if (!positive(t)) return -1.0;
    const Point2 &p = at(t[1]), &q = at(t[2]);
    if (-p.v >= 0.0 && q.v > 0.0) ++winding; // cross2(p, (1, 0)) >= 0 and cross2((1, 0), q) > 0
  }
  if (winding != 1) return -1.0;

  { // c, in the old patch
    const auto* t = locate(old_triangles_, at(2), w);
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
  const int n_points = static_cast<int>(projected_.size());
  hits_.resize(projected_.size() + 1);
  for (const auto& e : old_edges_) {
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
