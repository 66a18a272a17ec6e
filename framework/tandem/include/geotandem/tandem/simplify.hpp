#pragma once
// The working surface of the extended tandem algorithm (seed sections 2 and 3; ALGORITHM.md): it
// grows layer by layer, is simplified by edge collapses ordered by the Attali cost under the time
// lag and the extended time lag, tracks its connected components, and hands every finished
// component to a sink.
//
// Units: index coordinates of the whole cube (voxel units); E0 is in voxels.
// Thread safety: one WorkingSurface per thread.

#include <array>
#include <cstdint>
#include <memory>

#include "geotandem/core/cancel.hpp"
#include "geotandem/mesh/component.hpp"
#include "geotandem/mesh/surface.hpp"
#include "geotandem/tandem/layer.hpp"
#include "geotandem/tandem/region.hpp"
#include "geotandem/volume/geometry.hpp"

namespace geotandem::tandem {

namespace detail {
struct SurfaceAccess; // the wire format (serialize.hpp) reads and rebuilds the engine
} // namespace detail

// Defaults and their reasons are in docs/algorithm.md.
struct SimplifyOptions {
  // E0, in voxels, > 0: a guarantee. The simplified surface and the full-resolution marching-cubes
  // surface it came from are within E0 of each other (symmetric Hausdorff distance), for every
  // component and block count: every triangle carries a bound of how far the collapses moved the
  // surface mapped into it, and a collapse that would raise a bound above E0 is refused
  // (docs/algorithm.md). A collapse is also refused when its shape error sqrt(h_c(c)) exceeds E0.
  double max_error = 0.5;
  // alpha in [0, 1]: weight of the isotropy term against the shape term (the seed uses 0.4).
  double isotropy = 0.4;
  // Time lag (Attali): an edge may collapse only while reach(c) = height(c) + rad(c) is below the
  // front's rank. Off: only edges with a vertex on the front cross-section wait.
  bool time_lag = true;
  // Extended time lag (the seed's section 3.2): an edge may collapse only when the ball around
  // the midpoint of ab with radius rad(c) stays clear of the region's open faces. Off: only edges
  // with a vertex on an open face are frozen (the seed's comparison in its figure 9).
  bool extended_time_lag = true;
  // Our addition to the seed (docs/algorithm.md): c minimises eps_alpha on the plane where the
  // collapse leaves the enclosed volume unchanged. Without it the quadrics shrink convex bodies
  // (chords sag inside): about -2 % of volume at E0 = 0.1 and -10 % at E0 = 0.5 on a body of
  // radius 10 voxels. Off: c minimises eps_alpha freely, exactly as in the seed.
  bool preserve_volume = true;
  // The E0 guarantee (docs/algorithm.md): every vertex carries a distance bound and a collapse that
  // would raise one above E0 is refused, so that the simplified surface stays within E0 of the
  // full-resolution one (symmetric Hausdorff). Off: only eps_0(c) <= E0 is asked (an RMS-like
  // bound; measured maxima reach 2.5 to 4 E0), which keeps fewer triangles; for comparisons.
  bool guarantee_distance = true;
  // Storage: removed elements are compacted away (a fresh mesh of the live elements, which
  // renumbers everything) after a simplification or a dumping when more than this many triangles
  // and half the storage are dead. Tests lower it to exercise compaction on small inputs.
  std::size_t compaction_min_dead = 16384;

  // Throws InvalidArgument naming the field when a value is out of range.
  void validate() const;
};

// One accepted collapse ab -> c, as the constraints saw it (for observers and tests).
struct CollapseEvent {
  std::array<double, 3> a{}, b{}, c{};
  double height = 0.0; // height(c) = (height(a) + height(b)) / 2
  double rad = 0.0;    // rad(c) = (|a - b| + rad(a) + rad(b)) / 2
  double reach = 0.0;  // height + rad
  double front = 0.0;  // the front's rank when the collapse happened (+inf after the sweep)
  // Distance from the midpoint of ab to the nearest open face of the region (+inf: none).
  double open_face_distance = 0.0;
  double cost = 0.0;        // eps_alpha(c)
  double shape_error = 0.0; // eps_0(c) <= E0
  // The distance bound of the triangles around c after the collapse (<= E0): every point of the
  // full-resolution surface mapped into them lies within it of its image.
  double distance_bound = 0.0;
};

class CollapseObserver {
public:
  virtual ~CollapseObserver() = default;
  virtual void on_collapse(const CollapseEvent& event) = 0;
};

// Running totals of a working surface.
struct SimplifyCounters {
  std::uint64_t input_triangles = 0;
  std::uint64_t collapses = 0;
  std::uint64_t evaluations = 0;       // cost evaluations (candidates computed)
  std::uint64_t rejected_shape = 0;    // eps_0(c) > E0
  std::uint64_t rejected_link = 0;     // link condition (would change the topology)
  std::uint64_t rejected_flip = 0;     // a triangle would flip or degenerate
  std::uint64_t rejected_border = 0;   // c cannot stay on the cube faces both ends lie on
  std::uint64_t rejected_distance = 0; // the distance bound to full resolution would exceed E0
  std::uint64_t retried = 0;           // refused at c, requeued at a simpler position (fallback)
  std::uint64_t distrusted = 0;        // the minimiser lay far outside the patch: fallback position
  std::uint64_t blocked_by_faces = 0;  // times an edge was parked because of the open faces
  std::uint64_t components_dumped = 0;
  std::uint64_t triangles_dumped = 0;
  std::uint64_t garbage_collections = 0;

  // Every counter, in the order above: what the sums and the wire form go through, so that none is
  // forgotten (a merge once dropped the other side's rejected_distance).
  static constexpr std::array<std::uint64_t SimplifyCounters::*, 14> all = {
      &SimplifyCounters::input_triangles,  &SimplifyCounters::collapses,          &SimplifyCounters::evaluations,
      &SimplifyCounters::rejected_shape,   &SimplifyCounters::rejected_link,      &SimplifyCounters::rejected_flip,
      &SimplifyCounters::rejected_border,  &SimplifyCounters::rejected_distance,  &SimplifyCounters::retried,
      &SimplifyCounters::distrusted,       &SimplifyCounters::blocked_by_faces,   &SimplifyCounters::components_dumped,
      &SimplifyCounters::triangles_dumped, &SimplifyCounters::garbage_collections};
  // Their names, in the same order: the keys of the run statistics' "counters" (docs/store-format.md).
  static constexpr std::array<const char*, 14> names = {"input_triangles",  "collapses",          "evaluations",
                                                        "rejected_shape",   "rejected_link",      "rejected_flip",
                                                        "rejected_border",  "rejected_distance",  "retried",
                                                        "distrusted",       "blocked_by_faces",   "components_dumped",
                                                        "triangles_dumped", "garbage_collections"};

  SimplifyCounters& operator+=(const SimplifyCounters& other) {
    for (auto field : all)
      this->*field += other.*field;
    return *this;
  }
};
static_assert(sizeof(SimplifyCounters) == SimplifyCounters::all.size() * sizeof(std::uint64_t),
              "a counter is missing from SimplifyCounters::all");

class WorkingSurface {
public:
  // `cube`: the whole cube's geometry (its shape fixes the lattice ids and the cube faces; world
  // measures of dumped components use it). `region`: the blocks this surface covers (empty: the
  // whole cube). `axis`: the
  // extraction axis. `sink` receives finished components (may be null: they are then dropped
  // after counting, for benchmarks). `observer` (may be null) sees every collapse.
  // Throws InvalidArgument on invalid options, axis or geometry.
  WorkingSurface(const volume::Geometry& cube, Region region, int axis, const SimplifyOptions& options,
                 mesh::ComponentSink* sink, CollapseObserver* observer = nullptr);
  ~WorkingSurface();
  WorkingSurface(WorkingSurface&&) noexcept;
  WorkingSurface& operator=(WorkingSurface&&) noexcept;

  // extract(k) and delay(k): appends the layer's triangles (vertices that repeat an id of the
  // previous layer are welded to it) and parks every edge of the new triangles in W.
  // Layers must come in increasing rank along the surface's axis. Throws DataError when the layer
  // is malformed (index out of range, a triangle that would make the surface non-manifold, an id
  // repeated from a vertex that no longer exists) and InvalidArgument on a wrong axis or rank.
  // After a DataError the surface is in an unspecified state: drop it.
  void add_layer(const Layer& layer);
  // activate(k): the front moves to rank k (+infinity: past the end); every waiting edge whose
  // reach is now below the front becomes a candidate (if the open faces allow it).
  void activate(double front);
  // simplify(E0): collapses candidates in increasing cost until none is left. Checks `cancel`
  // now and then (throws Cancelled).
  void simplify(const CancelToken* cancel = nullptr);
  // dumping(): every component none of whose vertices is an endpoint of a waiting edge is
  // measured, handed to the sink and removed. Returns the number of components dumped.
  std::size_t dump();
  // activate(+inf); simplify; dump.
  void finish(const CancelToken* cancel = nullptr);
  // The region grows (a merge): edges parked by the open faces are tested again.
  void set_region(Region region);
  // Merge (the seed's section 3.2; docs/algorithm.md, "Blocks"): takes in the partial surface of
  // an adjacent region of the same cube. The meshes are united and the vertices both sides
  // carry on their common faces (original marching-cubes vertices, named by the same lattice-edge
  // id, at bit-identical positions) are welded into one, with their shape quadrics added; heights
  // and radii are kept; components joined through the seam become one (key: the smaller). The
  // region becomes the union of both regions (which may be L-shaped); the edges parked by the old
  // open faces are tested again against the new ones (extended time lag), the surface is
  // simplified, and every finished component is dumped. Returns the number dumped.
  // Both surfaces must be past their sweep (front +infinity: run_tandem and extract_block leave
  // them so) and share the cube, the axis and the simplify options; their regions must not
  // overlap. The larger of the two takes in the smaller in place (O(smaller) plus the seam's
  // simplification); the result, held by *this, keeps the sink and observer of *this; afterwards
  // `other` is empty and may only be destroyed or assigned to. Throws InvalidArgument when the
  // surfaces do not fit together (nothing is changed then), DataError when a shared lattice edge
  // has different positions on the two sides (*this is then in an unspecified state: drop it), and
  // Cancelled. After everything is merged: finish().
  std::size_t merge(WorkingSurface&& other, const CancelToken* cancel = nullptr);
  // Gives back the storage of removed elements and the room kept for growth: for a surface set
  // aside while its brother is extracted (the block driver and the workers call it). Costs a copy
  // of what is held; changes nothing else.
  void compact();

  const Region& region() const;
  double front() const;
  std::size_t triangle_count() const;     // triangles held now
  std::size_t vertex_count() const;       // vertices held now
  std::size_t component_count() const;    // components held now
  std::size_t waiting_edge_count() const; // |W|: delayed by the front or parked by open faces
  const SimplifyCounters& counters() const;

  // The triangles held now, as a plain surface (for tests and diagnostics).
  mesh::SurfaceMesh snapshot() const;

private:
  class Engine;
  friend struct detail::SurfaceAccess;
  explicit WorkingSurface(std::unique_ptr<Engine> engine);
  std::unique_ptr<Engine> engine_;
};

// Per thread, off by default: when on, a surface destroyed leaves its mesh's storage, emptied, to
// the next surface made on the same thread, so that leaf after leaf reuses the same pages (a
// worker turns it on: each of its leaves is merged into its surface and dropped). At most two
// meshes are kept, each with no more room than the largest one-block surface destroyed there
// needed. Turning it off gives them back, as release_surface_storage() does (for a driver about
// to need the memory more). The in-process block driver leaves it off: its surfaces are set aside
// or merged, never dropped after a leaf, so the spares only added to its peak.
void keep_surface_storage(bool on);
void release_surface_storage();

} // namespace geotandem::tandem
