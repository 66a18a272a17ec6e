#pragma once
// A cube's numbering, sampling and map as JSON, in one place for every file that records them: the
// raw sidecar's "geometry", the store's cube description and the synthetic cube's ground truth
// (each writes the shape, and whatever else it needs, beside these keys).

#include <nlohmann/json.hpp>

#include "geometry.hpp"

namespace geotandem::volume {

// inline0, inline_step, crossline0, crossline_step, z0, dz, z_unit ("ms", "m" or "ft"), affine
// {x0, xi, xj, y0, yi, yj}, in that order, then crs (crs_json) when the geometry has one.
nlohmann::ordered_json geometry_fields_json(const Geometry& geometry);

// {name, code, unit, unit_name, metres_per_unit, wkt}: everything a reader needs, without GDAL.
nlohmann::ordered_json crs_json(const Crs& crs);
// The inverse; throws InvalidArgument naming the key that is missing or mistyped.
Crs crs_from_json(const nlohmann::json& json);

} // namespace geotandem::volume
