#pragma once
// The tandem loop on one block (the seed's algorithms 2 and 4):
//   for each layer k: extract(k); delay(k); activate(k); simplify(E0); dumping();
//   then activate(inf); simplify(E0); dumping();
// and the brute-force route it is compared with (extract everything, then simplify once with the
// same cost). Both record, per layer, the triangles held in memory (the seed's figure 11).

#include <cstdint>
#include <memory>
#include <vector>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/mesh/component.hpp"
#include "geotandem/tandem/layer.hpp"
#include "geotandem/tandem/region.hpp"
#include "geotandem/tandem/simplify.hpp"
#include "geotandem/volume/box.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::tandem {

// Anything that hands out layers in increasing rank (marching cubes, tests' fixtures).
class LayerSource {
public:
  virtual ~LayerSource() = default;
  // Fills `layer` with the next layer; false when there is none left.
  virtual bool next(Layer& layer) = 0;
};

struct TandemOptions {
  float iso = 0.0f;           // isovalue (inside means value >= iso); used when extracting from a volume
  bool below = false;         // side: below, inside means value <= iso (McOptions::below)
  int axis = 0;               // extraction axis (0 = i, 1 = j, 2 = k)
  bool caps = true;           // close bodies cut by the cube's border (McOptions::caps)
  SimplifyOptions simplify{}; // E0, alpha, time lag, extended time lag
  // Dump finished components during the sweep (tandem with dumping). Off: the plain tandem keeps
  // them until the end of the block, as in the seed's comparison.
  bool dump = true;
  const CancelToken* cancel = nullptr;  // checked between layers and during long simplifications
  Progress* progress = nullptr;         // one unit per layer
  CollapseObserver* observer = nullptr; // sees every collapse (tests)
};

struct LayerStats {
  std::int64_t rank = 0;
  std::uint64_t input_triangles = 0;     // triangles this layer brought
  std::uint64_t triangles_in_memory = 0; // held by the working surface after the layer
  std::uint64_t vertices_in_memory = 0;
  std::uint64_t collapses = 0; // during this layer's simplification
  std::uint64_t rejected_shape = 0;
  std::uint64_t rejected_link = 0;
  std::uint64_t rejected_flip = 0;
  std::uint64_t components_dumped = 0;
  double seconds_extract = 0.0;  // producing the layer (marching cubes)
  double seconds_insert = 0.0;   // extract into the mesh + delay
  double seconds_simplify = 0.0; // activate + simplify
  double seconds_dump = 0.0;

  // Sets the collapses, refusals and dumps from two readings of the surface's counters.
  void count(const SimplifyCounters& before, const SimplifyCounters& after);
};

struct TandemStats {
  std::vector<LayerStats> layers;
  LayerStats final_pass;                 // activate(inf); simplify; dumping (rank = last rank + 1)
  SimplifyCounters counters;             // totals of the working surface
  std::uint64_t peak_triangles = 0;      // most triangles held at any layer boundary
  std::uint64_t remaining_triangles = 0; // still held at the end (components touching open faces)
  double seconds_total = 0.0;
};

// Runs the tandem on `surface` with layers from `source`. The surface keeps what touches its
// region's open faces (for a later merge). Throws what the source and the surface throw, and
// Cancelled.
TandemStats run_tandem(LayerSource& source, WorkingSurface& surface, const TandemOptions& options);
// Brute force on the same surface: every layer first, then one simplification and dumping.
TandemStats run_brute(LayerSource& source, WorkingSurface& surface, const TandemOptions& options);

// A layer source over marching cubes of `cells` of `volume` (options.iso, options.axis).
std::unique_ptr<LayerSource> marching_cubes_source(const volume::Volume& volume, const volume::Box& cells,
                                                   const TandemOptions& options);

// One block of a volume, start to finish: a working surface over the region made of `cells`
// alone (its open faces are the block faces inside the cube), the tandem loop (or brute force),
// finished components to `sink`. Returns the statistics; `remaining` (may be null) receives the
// working surface with what waits for a neighbour. Throws InvalidArgument on invalid options or
// cells outside the cube.
TandemStats extract_block(const volume::Volume& volume, const volume::Box& cells, const TandemOptions& options,
                          mesh::ComponentSink* sink, std::unique_ptr<WorkingSurface>* remaining = nullptr,
                          bool brute = false);

} // namespace geotandem::tandem
