#include "edge_cost.hpp"

#include <cmath>

#include "border_rule.hpp"

namespace geotandem::tandem::detail {

namespace {
// One corner's share of a triangle's terms: p x q and q - p for the two corners p, q that follow it
// (add_face_terms and remove_face_terms compute them with the same expressions).
inline void add_corner(VertexRecord& r, const Isotropy& isotropy, const Vec3& pq, const Vec3& link) {
  r.isotropy += isotropy;
  r.cross_sum = r.cross_sum + pq;
  r.link_sum = r.link_sum + link;
}
inline void remove_corner(VertexRecord& r, const Isotropy& isotropy, const Vec3& pq, const Vec3& link) {
  r.isotropy -= isotropy;
  r.cross_sum = r.cross_sum - pq;
  r.link_sum = r.link_sum - link;
}
} // namespace

EdgeCost::EdgeCost(HalfedgeMesh& mesh, const SimplifyOptions& options, const std::array<double, 3>& cube_hi)
    : mesh_(mesh), attali_(options.max_error, options.isotropy), max_error_(options.max_error),
      preserve_volume_(options.preserve_volume), cube_hi_(cube_hi) {}

// Every term of a face is computed here, from its first halfedge on and from the same positions,
// so that computing it again gives the bits that were added (working_mesh.hpp, FaceRecord).
inline EdgeCost::FaceCorners EdgeCost::corners(FH f) const {
  const HH h0 = mesh_.halfedge_handle(f);
  const HH h1 = mesh_.next_halfedge_handle(h0);
  FaceCorners c;
  c.v = {mesh_.from_vertex_handle(h0), mesh_.to_vertex_handle(h0), mesh_.to_vertex_handle(h1)};
  for (std::size_t k = 0; k < 3; ++k)
    c.p[k] = position(c.v[k]) - origin_;
  c.normal = cross(c.p[1] - c.p[0], c.p[2] - c.p[0]);
  return c;
}

inline Isotropy EdgeCost::face_isotropy(const FaceCorners& c) const {
  return Isotropy::of_triangle(position(c.v[0]), position(c.v[1]), position(c.v[2]), c.normal);
}

void EdgeCost::add_face_terms(FH f) {
  const FaceCorners c = corners(f);
  const Isotropy isotropy = face_isotropy(c);
  for (std::size_t k = 0; k < 3; ++k) {
    const Vec3 &p = c.p[(k + 1) % 3], &q = c.p[(k + 2) % 3];
    add_corner(vrec(c.v[k]), isotropy, cross(p, q), q - p);
  }
}

void EdgeCost::remove_face_terms(FH f, VH skip_a, VH skip_b) {
  // Computed again from the same positions in the same order: they cancel what add_face_terms
  // added exactly.
  const FaceCorners c = corners(f);
  const Isotropy isotropy = face_isotropy(c);
  for (std::size_t k = 0; k < 3; ++k) {
    if (c.v[k] == skip_a || c.v[k] == skip_b) continue;
    const Vec3 &p = c.p[(k + 1) % 3], &q = c.p[(k + 2) % 3];
    remove_corner(vrec(c.v[k]), isotropy, cross(p, q), q - p);
  }
}

void EdgeCost::recompute_face_terms() {
  for (std::size_t i = 0; i < mesh_.n_vertices(); ++i) {
    VertexRecord& r = mesh_.vertex_records()[i];
    r.isotropy = Isotropy{};
    r.cross_sum = {0.0, 0.0, 0.0};
    r.link_sum = {0.0, 0.0, 0.0};
  }
  for (std::size_t i = 0; i < mesh_.n_faces(); ++i)
    if (mesh_.face_records()[i].alive) add_face_terms(FH(static_cast<int>(i)));
}

void EdgeCost::volume_plane(HH h, const FaceCorners* const faces[2], CostInputs& in) const {
  // Six times the volume enclosed with a point s is the sum over triangles of det(p0 - s, p1 - s,
  // p2 - s). Moving a and b to c replaces, in every triangle (v, p, q) that keeps one of them,
  // det(v - s, p - s, q - s) by (c - s).((p - s) x (q - s)), and removes the two triangles of ab:
  // the volume is unchanged when (c - s).N = K, N summing (p - s) x (q - s) over the kept
  // triangles and K the determinants of all the triangles around a and b. Around an interior
  // vertex this does not depend on s; at a boundary (an open fan) it does, and s = midpoint of ab
  // keeps a flat patch flat. The per-vertex sums are taken from the origin o; with d = s - o,
  //   (p - s) x (q - s) = (p - o) x (q - o) - d x (q - p),   det_s(t) = det_o(t) - d.n_t.
  // A vertex keeps the sums of p x q and q - p over its triangles (v, p, q); those of det_o and
  // n_t follow from them and v (relative to o): v.(p x q), and p x q - v x (q - p).
  const VH a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
  const VertexRecord& ra = vrec(a);
  const VertexRecord& rb = vrec(b);
  const Vec3 pa = in.a - origin_, pb = in.b - origin_;
  Vec3 cross_sum = ra.cross_sum + rb.cross_sum;
  Vec3 link_sum = ra.link_sum + rb.link_sum;
  Vec3 normal_sum = cross_sum - (cross(pa, ra.link_sum) + cross(pb, rb.link_sum));
  double det_sum = dot(pa, ra.cross_sum) + dot(pb, rb.cross_sum);
  const HH sides[2] = {h, mesh_.opposite_halfedge_handle(h)};
  for (int k = 0; k < 2; ++k) {
    const FaceCorners* fc = faces[k];
    if (!fc) continue;
    // The triangle (u, v, w) of ab (side goes from u to v) is counted at both u and v, and in S_ab
    // once; it vanishes, so its terms at u and v leave N:
    //   (v x w) + (w x u) = w x (u - v)   and   (w - v) + (u - w) = u - v.
    det_sum -= dot(fc->p[0], cross(fc->p[1], fc->p[2]));
    normal_sum = normal_sum - fc->normal;
    // The face's corners from the side's start on.
    const VH from = mesh_.from_vertex_handle(sides[k]);
    const std::size_t i = fc->v[0] == from ? 0 : fc->v[1] == from ? 1 : 2;
    const Vec3& u = fc->p[i];
    const Vec3& v = fc->p[(i + 1) % 3];
    const Vec3& w = fc->p[(i + 2) % 3];
    cross_sum = cross_sum - cross(w, u - v);
    link_sum = link_sum - (u - v);
  }
  const Vec3 d = 0.5 * (in.a + in.b) - origin_;
  in.preserve_volume = true;
  in.volume_normal = cross_sum - cross(d, link_sum);
  in.volume_offset = det_sum - dot(d, normal_sum);
}

bool EdgeCost::inputs(HH h, CostInputs& in) const {
  const VH a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
  const VertexRecord& ra = vrec(a);
  const VertexRecord& rb = vrec(b);
  if (!border_allows_collapse(ra.border, rb.border)) return false;
  const unsigned border = ra.border | rb.border;
  in.shape = ra.shape + rb.shape;
  in.weight = ra.weight() + rb.weight();
  in.isotropy = ra.isotropy;
  in.isotropy += rb.isotropy;
  // The triangles abx and aby are in both sums.
  const FH f0 = mesh_.face_handle(h), f1 = mesh_.face_handle(mesh_.opposite_halfedge_handle(h));
  FaceCorners c0, c1;
  const FaceCorners* faces[2] = {nullptr, nullptr};
  if (f0.is_valid()) {
    c0 = corners(f0);
    in.isotropy -= face_isotropy(c0);
    faces[0] = &c0;
  }
  if (f1.is_valid()) {
    c1 = corners(f1);
    in.isotropy -= face_isotropy(c1);
    faces[1] = &c1;
  }
  in.a = position(a);
  in.b = position(b);
  if (preserve_volume_) volume_plane(h, faces, in);
  in.fixed_axes = 0;
  for (unsigned i = 0; i < 3; ++i) {
    const unsigned bits = (border >> (2 * i)) & 3u;
    if (bits == 0) continue;
    in.fixed_axes |= 1u << i;
    in.fixed_value[i] = bits == 1u ? 0.0 : cube_hi_[i];
  }
  return true;
}

bool EdgeCost::evaluate(HH h, Candidate& out, SimplifyCounters& counters, CostInputs& in) const {
  if (!inputs(h, in)) {
    ++counters.rejected_border;
    return false;
  }
  ++counters.evaluations;
  const auto prepared = attali_.prepare(in);
  out = attali_.best(prepared);
  if (out.fallback) ++counters.distrusted;
  if (!(out.shape_error <= max_error_)) {
    ++counters.rejected_shape;
    return false;
  }
  return true;
}

} // namespace geotandem::tandem::detail
