#pragma once
// Reading one component of the working mesh out as a plain surface, for dumping: its vertices and
// triangles, found by a traversal of one-rings from any member vertex and numbered in the order
// the traversal reaches them. It also lists what it visited, so that the engine can take the
// component's elements out of the mesh and the queues afterwards.

#include <cstdint>
#include <vector>

#include "collapse_ops.hpp"
#include "geotandem/mesh/surface.hpp"
#include "working_mesh.hpp"

namespace geotandem::tandem::detail {

class ComponentReader {
public:
  // The component holding `start`: each vertex once, in the mesh's coordinates, and each triangle
  // once with its orientation. `vertices` and `faces` receive the mesh elements visited (vertices
  // in the surface's numbering). `marks` is scratch shared with the link test.
  mesh::SurfaceMesh read(const HalfedgeMesh& mesh, const HalfedgeMesh::Point* points, VH start, VertexMarks& marks,
                         std::vector<VH>& vertices, std::vector<FH>& faces);
  // Gives the storage back (the mesh was compacted: vertex numbers changed).
  void release() { std::vector<std::int32_t>().swap(local_index_); }

private:
  std::vector<std::int32_t> local_index_; // by mesh vertex: its number in the component read last
};

} // namespace geotandem::tandem::detail
