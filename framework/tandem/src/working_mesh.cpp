// The working mesh's storage: single elements, growth, and compaction in place.
#include "working_mesh.hpp"

namespace geotandem::tandem::detail {

VH HalfedgeMesh::add_vertex(const Point& p) {
  out_.push_back(HH());
  points_.push_back(p);
  VertexRecord r;
  r.alive = true;
  vertices_.push_back(r);
  return VH(static_cast<int>(out_.size() - 1));
}

HH HalfedgeMesh::new_edge(VH from, VH to) {
  const HH h(static_cast<int>(halfedges_.size()));
  halfedges_.push_back({to, HH(), HH(), FH()});
  halfedges_.push_back({from, HH(), HH(), FH()});
  EdgeRecord r;
  r.alive = true;
  edges_.push_back(r);
  return h;
}

FH HalfedgeMesh::new_face() {
  face_halfedge_.push_back(HH());
  FaceRecord r;
  r.alive = true;
  faces_.push_back(r);
  return FH(static_cast<int>(face_halfedge_.size() - 1));
}

void HalfedgeMesh::resize(std::size_t nv, std::size_t ne, std::size_t nf) {
  out_.resize(nv, HH());
  points_.resize(nv, Point(0.0, 0.0, 0.0));
  vertices_.resize(nv, VertexRecord{});
  halfedges_.resize(2 * ne, Halfedge{VH(), HH(), HH(), FH()});
  edges_.resize(ne, EdgeRecord{});
  face_halfedge_.resize(nf, HH());
  faces_.resize(nf, FaceRecord{});
}

void HalfedgeMesh::clear() {
  for_each_array(*this, 0, 0, 0, [](auto& array, std::size_t) { array.clear(); });
}

void HalfedgeMesh::trim(std::size_t nv, std::size_t ne, std::size_t nf) {
  for_each_array(*this, nv, ne, nf, [](auto& array, std::size_t n) { array.trim(n); });
}

std::size_t HalfedgeMesh::capacity_bytes() const {
  std::size_t bytes = 0;
  for_each_array(*this, 0, 0, 0,
                 [&bytes](const auto& array, std::size_t) { bytes += array.capacity() * sizeof(*array.data()); });
  return bytes;
}

void HalfedgeMesh::reserve(std::size_t nv, std::size_t ne, std::size_t nf) {
  for_each_array(*this, nv, ne, nf, [](auto& array, std::size_t n) { array.reserve(n); });
}

std::vector<std::int32_t> HalfedgeMesh::compact(bool give_back) {
  const std::size_t nv = n_vertices(), ne = n_edges(), nf = n_faces();
  std::vector<std::int32_t> vmap(nv, -1), emap(ne, -1), fmap(nf, -1);
  std::int32_t cv = 0, ce = 0, cf = 0;
  for (std::size_t i = 0; i < nv; ++i)
    if (vertices_[i].alive) vmap[i] = cv++;
  for (std::size_t i = 0; i < ne; ++i)
    if (edges_[i].alive) emap[i] = ce++;
  for (std::size_t i = 0; i < nf; ++i)
    if (faces_[i].alive) fmap[i] = cf++;

  const auto halfedge = [&](HH h) { return h.is_valid() ? HH(2 * emap[idx(h) >> 1] + (h.idx() & 1)) : HH(); };
  // Element i moves to k <= i, in increasing order: each is read before anything is written over
  // it (a move to k == i reads the element whole first).
  for (std::size_t i = 0; i < nv; ++i) {
    const std::int32_t k = vmap[i];
    if (k < 0) continue;
    const auto to = static_cast<std::size_t>(k);
    out_[to] = halfedge(out_[i]);
    points_[to] = points_[i];
    vertices_[to] = vertices_[i];
  }
  for (std::size_t i = 0; i < ne; ++i) {
    const std::int32_t k = emap[i];
    if (k < 0) continue;
    const auto to = static_cast<std::size_t>(k);
    for (std::size_t side = 0; side < 2; ++side) {
      const Halfedge from = halfedges_[2 * i + side];
      halfedges_[2 * to + side] = {VH(vmap[idx(from.to)]), halfedge(from.next), halfedge(from.prev),
                                   from.face.is_valid() ? FH(fmap[idx(from.face)]) : FH()};
    }
    edges_[to] = edges_[i];
  }
  for (std::size_t i = 0; i < nf; ++i) {
    const std::int32_t k = fmap[i];
    if (k < 0) continue;
    const auto to = static_cast<std::size_t>(k);
    face_halfedge_[to] = halfedge(face_halfedge_[i]);
    faces_[to] = faces_[i];
  }
  resize(static_cast<std::size_t>(cv), static_cast<std::size_t>(ce), static_cast<std::size_t>(cf));
  if (give_back) trim(0, 0, 0); // every byte beyond the live elements
  return vmap;
}

} // namespace geotandem::tandem::detail
