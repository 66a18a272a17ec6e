#include "component_reader.hpp"

namespace geotandem::tandem::detail {

mesh::SurfaceMesh ComponentReader::read(const HalfedgeMesh& mesh, const HalfedgeMesh::Point* points, VH start,
                                        VertexMarks& marks, std::vector<VH>& order, std::vector<FH>& faces) {
  if (local_index_.size() < mesh.n_vertices()) local_index_.resize(mesh.n_vertices(), -1);
  order.clear();
  faces.clear();
  const std::uint32_t stamp = marks.next_stamp();
  marks.mark(start, stamp);
  order.push_back(start);
  for (std::size_t next = 0; next < order.size(); ++next) {
    const VH v = order[next];
    local_index_[static_cast<std::size_t>(v.idx())] = static_cast<std::int32_t>(next);
    const HH first = mesh.halfedge_handle(v);
    HH h = first;
    do {
      const VH w = mesh.to_vertex_handle(h);
      if (!marks.marked(w, stamp)) {
        marks.mark(w, stamp);
        order.push_back(w);
      }
      const FH f = mesh.face_handle(h);
      if (f.is_valid() && mesh.halfedge_handle(f) == h) faces.push_back(f); // each face once
      h = next_outgoing(mesh, h);
    } while (h != first);
  }
  mesh::SurfaceMesh surface;
  surface.points.reserve(order.size());
  for (VH v : order)
    surface.points.push_back(to_vec(points[v.idx()]));
  surface.triangles.reserve(faces.size());
  const auto local = [this](VH v) {
    return static_cast<std::uint32_t>(local_index_[static_cast<std::size_t>(v.idx())]);
  };
  for (FH f : faces) {
    const HH h = mesh.halfedge_handle(f);
    surface.triangles.push_back({local(mesh.from_vertex_handle(h)), local(mesh.to_vertex_handle(h)),
                                 local(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)))});
  }
  return surface;
}

} // namespace geotandem::tandem::detail
