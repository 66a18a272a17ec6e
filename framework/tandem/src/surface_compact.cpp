// Compaction of the working mesh after dumpings: a fresh mesh holding only the live elements.
// OpenMesh's garbage collection swaps every property of every element into place (virtual calls
// per element and property); after a dumping the live part is usually a small fraction, so
// copying it is much cheaper, and the fresh, dense storage keeps the hot loops in cache.
#include "surface_engine.hpp"

namespace geotandem::tandem {

std::vector<std::int32_t> WorkingSurface::Engine::rebuild_mesh() {
  const detail::TriMesh& old = *mesh_;
  const std::size_t nv = old.n_vertices(), ne = old.n_edges(), nf = old.n_faces();
  std::vector<std::int32_t> vmap(nv, -1), emap(ne, -1), fmap(nf, -1);
  std::int32_t cv = 0, ce = 0, cf = 0;
  for (std::size_t i = 0; i < nv; ++i)
    if (vrec_[i].alive) vmap[i] = cv++;
  for (std::size_t i = 0; i < ne; ++i)
    if (erec_[i].alive) emap[i] = ce++;
  for (std::size_t i = 0; i < nf; ++i)
    if (frec_[i].alive) fmap[i] = cf++;

  auto fresh = std::make_unique<detail::TriMesh>();
  OpenMesh::VPropHandleT<detail::VertexRecord> vprop;
  OpenMesh::EPropHandleT<detail::EdgeRecord> eprop;
  OpenMesh::FPropHandleT<detail::FaceRecord> fprop;
  fresh->add_property(vprop, "geotandem:vertex");
  fresh->add_property(eprop, "geotandem:edge");
  fresh->add_property(fprop, "geotandem:face");
  fresh->resize(static_cast<std::size_t>(cv), static_cast<std::size_t>(ce), static_cast<std::size_t>(cf));
  detail::TriMesh::Point* points = fresh->property(fresh->points_pph()).data_vector().data();
  detail::VertexRecord* vrec = fresh->property(vprop).data_vector().data();
  detail::EdgeRecord* erec = fresh->property(eprop).data_vector().data();
  detail::FaceRecord* frec = fresh->property(fprop).data_vector().data();

  auto halfedge = [&](HH h) {
    return h.is_valid() ? HH(2 * emap[static_cast<std::size_t>(h.idx() >> 1)] + (h.idx() & 1)) : HH();
  };
  for (std::size_t i = 0; i < nv; ++i) {
    const std::int32_t k = vmap[i];
    if (k < 0) continue;
    points[k] = points_[i];
    vrec[k] = vrec_[i];
    fresh->set_halfedge_handle(VH(k), halfedge(old.halfedge_handle(VH(static_cast<int>(i)))));
  }
  for (std::size_t i = 0; i < ne; ++i) {
    const std::int32_t k = emap[i];
    if (k < 0) continue;
    erec[k] = erec_[i];
    for (int side = 0; side < 2; ++side) {
      const HH from(2 * static_cast<int>(i) + side), to(2 * k + side);
      fresh->set_vertex_handle(to, VH(vmap[static_cast<std::size_t>(old.to_vertex_handle(from).idx())]));
      fresh->set_next_halfedge_handle(to, halfedge(old.next_halfedge_handle(from)));
      const FH f = old.face_handle(from);
      if (f.is_valid()) fresh->set_face_handle(to, FH(fmap[static_cast<std::size_t>(f.idx())]));
    }
  }
  for (std::size_t i = 0; i < nf; ++i) {
    const std::int32_t k = fmap[i];
    if (k < 0) continue;
    frec[k] = frec_[i];
    fresh->set_halfedge_handle(FH(k), halfedge(old.halfedge_handle(FH(static_cast<int>(i)))));
  }
  mesh_ = std::move(fresh);
  vprop_ = vprop;
  eprop_ = eprop;
  fprop_ = fprop;
  return vmap;
}

} // namespace geotandem::tandem
