#pragma once
// The machinery behind WorkingSurface, as two objects with one job each and the steps that use
// both: the storage (surface_storage.hpp: the working mesh, its records, the components, the ids
// that weld a layer to the previous one; growth, compaction, one bulk-append path) and the
// collapser (collapser.hpp: the queues, the cost, the distance bound, the collapses). The engine
// appends layers (surface_layers.cpp), dumps finished components and compacts (surface_dump.cpp),
// merges (surface_merge.cpp) and exports and imports its state (surface_state.cpp).

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "collapser.hpp"
#include "component_reader.hpp"
#include "geotandem/tandem/simplify.hpp"
#include "surface_state.hpp"
#include "surface_storage.hpp"

namespace geotandem::tandem {

class WorkingSurface::Engine {
public:
  Engine(const volume::Geometry& cube, Region region, int axis, const SimplifyOptions& options,
         mesh::ComponentSink* sink, CollapseObserver* observer);
  // With keep_surface_storage() on, leaves its mesh's room to the next surface made on this thread.
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  void add_layer(const Layer& layer);
  void activate(double front);
  void simplify(const CancelToken* cancel);
  std::size_t dump();
  void set_region(Region region);
  void compact();

  const Region& region() const { return region_; }
  double front() const { return collapser_.front(); }
  std::size_t triangle_count() const { return storage_.live_faces(); }
  std::size_t vertex_count() const { return storage_.live_vertices(); }
  std::size_t component_count() const { return storage_.components().alive_count(); }
  std::size_t waiting_edge_count() const { return collapser_.queues().waiting_count(); }
  const SimplifyCounters& counters() const { return collapser_.counters(); }
  mesh::SurfaceMesh snapshot() const { return storage_.snapshot(); }

  // The surface as plain data, live elements only, densely numbered (surface_state.cpp).
  detail::SurfaceState export_state() const;
  // Fills a freshly constructed engine (same cube, region, axis and options as the state) with
  // `state`: the mesh, the records, the queues and the components. Throws DataError when the state
  // is inconsistent (an index out of range, a triangle that would make the surface non-manifold,
  // an edge that is not in the mesh).
  void import_state(detail::SurfaceState&& state);
  // Takes in the surface of a disjoint region of the same cube (both past their sweep), as plain
  // data (exported from its engine, or decoded from its wire form), welded by lattice ids; the
  // region becomes the union, but the parked edges are not placed again yet (surface_merge.cpp).
  // Throws InvalidArgument when the surfaces do not fit together and DataError when the weld does
  // not (two vertices with the same lattice id differ in position, a welded vertex is not on this
  // side's boundary, a seam edge is used in one direction twice): nothing is changed then; a
  // DataError from a triangle that still cannot go in leaves the engine in an unspecified state. The
  // state's parts are given back as soon as they are in: the larger surface grows while they go.
  void absorb_state(detail::SurfaceState&& other);
  // absorb_state(), then the edges parked by faces now inside the grown region placed again, the
  // simplification and the dumping: a whole merge. Returns the components dumped.
  std::size_t merge_state(detail::SurfaceState&& other, const CancelToken* cancel);
  // The union of both regions; throws InvalidArgument as absorb_state() does when the two do not
  // fit.
  Region merge_region(const Engine& other) const;
  Region merge_region_state(const detail::SurfaceState& other) const;
  Region merge_region_of(const Region& region, int axis, const SimplifyOptions& options, double front) const;
  mesh::ComponentSink* sink_of() const { return sink_; }
  CollapseObserver* observer_of() const { return collapser_.observer(); }
  void set_outputs(mesh::ComponentSink* sink, CollapseObserver* observer) {
    sink_ = sink;
    collapser_.set_observer(observer);
  }

private:
  using VH = detail::VH;
  using HH = detail::HH;
  using EH = detail::EH;
  using FH = detail::FH;

  // Layers (surface_layers.cpp): a vertex of the layer welded to the previous layer by its lattice
  // id, or a new one (numbered after the mesh's; its storage is made for the whole layer at once).
  VH weld_or_create(std::uint64_t id, const std::array<double, 3>& p, std::int64_t rank, std::size_t index);

  // Dumping and compaction (surface_dump.cpp).
  void dump_component(std::int32_t root);
  void maybe_collect_garbage();
  // Compacts the mesh; `give_back` returns the room beyond the live elements (a surface set aside),
  // else the room stays for the layers still to come (a surface being swept: the room freed now
  // would be faulted in again within a few layers).
  void collect_garbage(bool give_back);

  volume::Geometry cube_;
  Region region_;
  int axis_;
  mesh::ComponentSink* sink_;
  detail::SurfaceStorage storage_;
  detail::Collapser collapser_;
  detail::ComponentReader reader_; // reads a finished component out for dumping
  std::int64_t last_rank_ = std::numeric_limits<std::int64_t>::min();
};

} // namespace geotandem::tandem
