#pragma once
// A cube's numbering, sampling and map as JSON, in one place for every file that records them: the
// raw sidecar's "geometry", the store's cube description and the synthetic cube's ground truth
// (each writes the shape, and whatever else it needs, beside these keys).

#include <nlohmann/json.hpp>

#include "geometry.hpp"

namespace geotandem::volume {

// inline0, inline_step, crossline0, crossline_step, z0, dz, z_unit ("ms" or "m") and affine
// {x0, xi, xj, y0, yi, yj}, in that order.
nlohmann::ordered_json geometry_fields_json(const Geometry& geometry);

} // namespace geotandem::volume
