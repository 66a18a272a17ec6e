// Map polygons (volume/geopackage.hpp) without GDAL: their area.

#include <cmath>

#include "geotandem/volume/geopackage.hpp"

namespace geotandem::volume {

double area_of(const std::vector<MapPolygon>& polygons) {
  // Relative to the ring's first point: at map coordinates of 10^6 m the products of raw
  // coordinates are about 10^13 and their difference, the area, would lose about 10^-3 m^2 a vertex.
  auto ring_area = [](const MapRing& ring) {
    if (ring.size() < 3) return 0.0;
    const MapPoint& o = ring.front();
    double twice = 0.0;
    for (std::size_t n = 1; n + 1 < ring.size(); ++n) {
      const double ax = ring[n][0] - o[0], ay = ring[n][1] - o[1];
      const double bx = ring[n + 1][0] - o[0], by = ring[n + 1][1] - o[1];
      twice += ax * by - bx * ay;
    }
    return std::abs(twice) / 2.0;
  };
  double area = 0.0;
  for (const MapPolygon& p : polygons) {
    area += ring_area(p.outer);
    for (const MapRing& hole : p.holes)
      area -= ring_area(hole);
  }
  return area;
}

} // namespace geotandem::volume
