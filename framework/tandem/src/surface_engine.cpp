#include "surface_engine.hpp"

#include <cmath>
#include <string>

#include "geotandem/core/error.hpp"
#include "geotandem/tandem/marching_cubes.hpp"

namespace geotandem::tandem {

namespace {
// The cube's last sample index on each axis: the far faces a border vertex stays on.
std::array<double, 3> last_indices(const volume::Geometry& cube) {
  std::array<double, 3> hi{};
  for (int i = 0; i < 3; ++i)
    hi[static_cast<std::size_t>(i)] = static_cast<double>(cube.shape[i] - 1);
  return hi;
}

// The region checked against the cube (the whole cube when empty), with the other arguments,
// before anything refers to them.
Region checked_region(const volume::Geometry& cube, Region region, int axis, const SimplifyOptions& options) {
  options.validate();
  cube.validate();
  if (axis < 0 || axis > 2)
    throw InvalidArgument("working surface: extraction axis " + std::to_string(axis) + " is not 0, 1 or 2");
  const volume::Box cells = cube_cells(cube.shape);
  if (region.empty()) region = Region::block(cells, cells);
  if (!(region.cube() == cells))
    throw InvalidArgument("working surface: the region's cube " + region.cube().to_string() +
                              " is not the cells of the cube " + cells.to_string(),
                          {}, "build the region from cube_cells(geometry.shape)");
  return region;
}
} // namespace

WorkingSurface::Engine::~Engine() {
  storage_.give_back_room(region_.blocks().size() == 1);
}

WorkingSurface::Engine::Engine(const volume::Geometry& cube, Region region, int axis, const SimplifyOptions& options,
                               mesh::ComponentSink* sink, CollapseObserver* observer)
    : cube_(cube), region_(checked_region(cube, std::move(region), axis, options)), axis_(axis), sink_(sink),
      storage_(last_indices(cube)), collapser_(storage_, region_, axis, options, last_indices(cube), observer) {
  detail::Vec3 origin;
  for (std::size_t i = 0; i < 3; ++i)
    origin[i] = static_cast<double>(region_.blocks().front().lo[i]);
  collapser_.costs().set_origin(origin);
}

void WorkingSurface::Engine::activate(double front) {
  collapser_.activate(front);
  if (std::isinf(front)) storage_.drop_isolated_vertices(); // no layer will use them now
}

void WorkingSurface::Engine::set_region(Region region) {
  if (!(region.cube() == region_.cube()))
    throw InvalidArgument("working surface: the new region " + region.to_string() + " is not in the same cube as " +
                          region_.to_string());
  region_ = std::move(region);
  collapser_.place_parked();
}

void WorkingSurface::Engine::simplify(const CancelToken* cancel) {
  collapser_.simplify(cancel);
  // Storage freed by the collapses is reclaimed here too, not only after a dumping: the tandem
  // without dumping would otherwise hold as much as brute force.
  maybe_collect_garbage();
}

} // namespace geotandem::tandem
