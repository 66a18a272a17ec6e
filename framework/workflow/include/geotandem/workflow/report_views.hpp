#pragma once
// What the report's body views draw, taken from a component store: the survey's outline, and
// every kept body's surface decimated for display (vertex clustering until the triangle budget
// holds) with the convex hull of its full-resolution footprint.

#include <cstddef>
#include <vector>

#include "geotandem/core/cancel.hpp"
#include "geotandem/mesh/surface.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/volume/geometry.hpp"
#include "geotandem/workflow/report.hpp"

namespace geotandem::workflow {

// The outline of the traces' centres and the first and last sample.
ReportSurvey survey_outline(const volume::Geometry& geometry);

// The kept components of `components` (the `max_bodies` with the most triangles when there are
// more, in their order in `components`), read from `store` (world coordinates), each decimated to
// its share of `budget` in proportion to its triangles. Throws what ComponentStore::read throws, and
// Cancelled between bodies once `cancel` (when given) is cancelled.
std::vector<ReportBody> display_bodies(const store::ComponentStore& store,
                                       const std::vector<ReportComponent>& components, const ReportSurvey& survey,
                                       std::size_t budget = kDisplayTriangleBudget,
                                       std::size_t max_bodies = kDisplayBodies, const CancelToken* cancel = nullptr);

// One body: `world` decimated to at most `budget` triangles (points relative to `origin`, z
// scaled by `z_scale` while clustering so that cells are cubes on screen), and its footprint.
ReportBody display_body(const ReportComponent& component, const mesh::SurfaceMesh& world,
                        const std::array<double, 2>& origin, double z_scale, std::size_t budget);

// The convex hull of points, counter-clockwise, without collinear points (Andrew's monotone chain).
std::vector<std::array<double, 2>> convex_hull(std::vector<std::array<double, 2>> points);

} // namespace geotandem::workflow
