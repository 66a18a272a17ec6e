// Map polygons (volume/geopackage.hpp) without GDAL: their area.

#include <cmath>

#include "geotandem/volume/geopackage.hpp"

namespace geotandem::volume {

double area_of(const std::vector<MapPolygon>& polygons) {
  auto ring_area = [](const MapRing& ring) {
    double twice = 0.0;
    for (std::size_t n = 0; n < ring.size(); ++n) {
      const MapPoint& a = ring[n];
      const MapPoint& b = ring[(n + 1) % ring.size()];
      twice += a[0] * b[1] - b[0] * a[1];
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
