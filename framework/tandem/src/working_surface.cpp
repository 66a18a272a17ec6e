#include <cmath>
#include <limits>
#include <string>

#include "geotandem/core/error.hpp"
#include "geotandem/tandem/simplify.hpp"
#include "surface_engine.hpp"

namespace geotandem::tandem {

void SimplifyOptions::validate() const {
  if (!(max_error > 0.0) || !std::isfinite(max_error))
    throw InvalidArgument("simplify: max_error (E0) must be a positive number of voxels, got " +
                              std::to_string(max_error),
                          {}, "0.5 voxel is the default");
  if (!(isotropy >= 0.0 && isotropy <= 1.0))
    throw InvalidArgument("simplify: isotropy (alpha) must lie in [0, 1], got " + std::to_string(isotropy), {},
                          "the seed recommends 0.4");
}

WorkingSurface::WorkingSurface(const volume::Geometry& cube, Region region, int axis, const SimplifyOptions& options,
                               mesh::ComponentSink* sink, CollapseObserver* observer)
    : engine_(std::make_unique<Engine>(cube, std::move(region), axis, options, sink, observer)) {}
WorkingSurface::WorkingSurface(std::unique_ptr<Engine> engine) : engine_(std::move(engine)) {}
WorkingSurface::~WorkingSurface() = default;
WorkingSurface::WorkingSurface(WorkingSurface&&) noexcept = default;
WorkingSurface& WorkingSurface::operator=(WorkingSurface&&) noexcept = default;

void WorkingSurface::add_layer(const Layer& layer) {
  engine_->add_layer(layer);
}
void WorkingSurface::activate(double front) {
  engine_->activate(front);
}
void WorkingSurface::simplify(const CancelToken* cancel) {
  engine_->simplify(cancel);
}
std::size_t WorkingSurface::dump() {
  return engine_->dump();
}
void WorkingSurface::finish(const CancelToken* cancel) {
  engine_->activate(std::numeric_limits<double>::infinity());
  engine_->simplify(cancel);
  engine_->dump();
}
void WorkingSurface::set_region(Region region) {
  engine_->set_region(std::move(region));
}
std::size_t WorkingSurface::merge(WorkingSurface&& other, const CancelToken* cancel) {
  if (&other == this || !other.engine_ || !engine_)
    throw InvalidArgument("merge: a surface merges with another, non-empty surface");
  engine_->merge_region(*other.engine_); // refuses surfaces that do not fit before anything moves
  // The larger surface takes in the smaller one; the result keeps this surface's sink and observer.
  if (engine_->triangle_count() < other.engine_->triangle_count()) {
    other.engine_->set_outputs(engine_->sink_of(), engine_->observer_of());
    std::swap(engine_, other.engine_);
  }
  // The smaller side as plain data, then its engine goes before the larger one grows: the two
  // engines and the state are never held at once.
  detail::SurfaceState state = other.engine_->export_state();
  { const WorkingSurface gone = std::move(other); }
  return engine_->merge_state(std::move(state), cancel);
}

void WorkingSurface::compact() {
  engine_->compact();
}

const Region& WorkingSurface::region() const {
  return engine_->region();
}
double WorkingSurface::front() const {
  return engine_->front();
}
std::size_t WorkingSurface::triangle_count() const {
  return engine_->triangle_count();
}
std::size_t WorkingSurface::vertex_count() const {
  return engine_->vertex_count();
}
std::size_t WorkingSurface::component_count() const {
  return engine_->component_count();
}
std::size_t WorkingSurface::waiting_edge_count() const {
  return engine_->waiting_edge_count();
}
const SimplifyCounters& WorkingSurface::counters() const {
  return engine_->counters();
}
mesh::SurfaceMesh WorkingSurface::snapshot() const {
  return engine_->snapshot();
}

} // namespace geotandem::tandem
