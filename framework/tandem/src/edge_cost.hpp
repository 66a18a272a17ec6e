#pragma once
// The cost of collapsing an edge of the working mesh, kept ready as the surface changes: each
// vertex's sums of the isotropy and volume terms of the triangles around it (in its
// VertexRecord), the inputs of an edge's cost read from them (quadrics, isotropy, volume plane,
// the cube faces that hold c), and the evaluation by the Attali cost (attali_cost.hpp).
//
// The collapser (collapser.hpp) tells it which triangles join or leave the surface; it owns the
// sums' bookkeeping and nothing else: no queue, no component, no collapse.

#include <array>

#include "attali_cost.hpp"
#include "geotandem/tandem/simplify.hpp"
#include "working_mesh.hpp"

namespace geotandem::tandem::detail {

class EdgeCost {
public:
  // `mesh` outlives this object; `cube_hi` is the cube's last sample index on each axis (the faces
  // a border vertex stays on).
  // The records are read through the mesh each time, so growth and compaction move nothing here.
  EdgeCost(HalfedgeMesh& mesh, const SimplifyOptions& options, const std::array<double, 3>& cube_hi);

  // Volume terms are computed relative to the origin (the first block's corner, carried by a
  // surface's state), so that their sums keep their precision far from the cube's corner.
  const Vec3& origin() const { return origin_; }
  void set_origin(const Vec3& origin) { origin_ = origin; }
  const AttaliCost& attali() const { return attali_; }

  // A triangle's terms into or out of its corners' sums (out of all but skip_a and skip_b).
  void add_face_terms(FH f);
  void remove_face_terms(FH f, VH skip_a, VH skip_b);
  // Every vertex's sums from scratch over the live faces: the running sums drift by rounding over
  // many collapses.
  void recompute_face_terms();

  // The inputs of the cost of collapsing h; false when the cube faces forbid the collapse (its ends
  // carry both sides of one axis).
  bool inputs(HH h, CostInputs& in) const;
  // The best position and its cost; false (counted in `counters`) when the faces forbid the
  // collapse or the shape error at the best position exceeds E0.
  bool evaluate(HH h, Candidate& out, SimplifyCounters& counters) const {
    CostInputs in;
    return evaluate(h, out, counters, in);
  }
  // The same, keeping the inputs it read in `in` (valid unless the faces forbade the collapse).
  bool evaluate(HH h, Candidate& out, SimplifyCounters& counters, CostInputs& in) const;

private:
  // A face's corners from its first halfedge on, their positions relative to the origin and its
  // normal (p1 - p0) x (p2 - p0): what every term of the face is computed from, so that computing
  // them again gives the bits that were added (working_mesh.hpp, FaceRecord).
  struct FaceCorners {
    std::array<VH, 3> v;
    std::array<Vec3, 3> p;
    Vec3 normal;
  };
  FaceCorners corners(FH f) const;
  Isotropy face_isotropy(const FaceCorners& c) const;
  Vec3 position(VH v) const { return to_vec(mesh_.points()[v.idx()]); }
  VertexRecord& vrec(VH v) const { return mesh_.vertex_records()[v.idx()]; }
  // The plane on which collapsing h keeps the enclosed volume; `faces`: the corners of the
  // triangles on both sides of h (null where there is none).
  void volume_plane(HH h, const FaceCorners* const faces[2], CostInputs& in) const;

  HalfedgeMesh& mesh_;
  AttaliCost attali_;
  double max_error_;
  bool preserve_volume_;
  std::array<double, 3> cube_hi_;
  Vec3 origin_{};
};

} // namespace geotandem::tandem::detail
