#include "parked_edges.hpp"

#include <algorithm>

namespace geotandem::tandem::detail {

void ParkedEdges::near(const volume::Box& cells, double margin, std::vector<std::int32_t>& out) const {
  out.clear();
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = static_cast<double>(cells.lo[a]);
    hi[a] = static_cast<double>(cells.hi[a]);
  }
  for (std::size_t n = 0; n < items_.size(); ++n) {
    const Spot& s = spots_[n];
    const double p[3] = {s.x, s.y, s.z};
    double d2 = 0.0; // squared distance from the midpoint to the box
    for (int a = 0; a < 3; ++a) {
      const double d = std::max({lo[a] - p[a], p[a] - hi[a], 0.0});
      d2 += d * d;
    }
    const double reach = static_cast<double>(s.radius) + margin;
    if (reach >= 0.0 && d2 <= reach * reach) out.push_back(items_[n]);
  }
}

} // namespace geotandem::tandem::detail
