// Cap triangles on the cube's outer planes, and the names of the cut faces.
#include "geotandem/mesh/caps.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/component.hpp"

namespace geotandem::mesh {

namespace {
// Cap vertices sit on samples or lattice edges of the plane: exact in index coordinates; the
// tolerance only absorbs surfaces that went through float storage.
constexpr double kPlaneTolerance = 1e-6;
constexpr const char* kFaceNames[6] = {"i-", "i+", "j-", "j+", "k-", "k+"};
} // namespace

std::uint8_t outer_planes(const Point& p, const volume::Index3& shape) {
  std::uint8_t bits = 0;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(p[a]) <= kPlaneTolerance) bits |= static_cast<std::uint8_t>(1u << (2 * a));
    if (std::abs(p[a] - static_cast<double>(shape[a] - 1)) <= kPlaneTolerance)
      bits |= static_cast<std::uint8_t>(2u << (2 * a));
  }
  return bits;
}

int cap_face(const SurfaceMesh& s, const Triangle& t, const volume::Index3& shape) {
  const Point& p = s.points[t[0]];
  const Point& q = s.points[t[1]];
  const Point& r = s.points[t[2]];
  const unsigned common = outer_planes(p, shape) & outer_planes(q, shape) & outer_planes(r, shape);
  if (common == 0) return -1;
  for (int bit = 0; bit < 6; ++bit) {
    if (((common >> bit) & 1u) == 0) continue;
    const int a = bit / 2, u = (a + 1) % 3, v = (a + 2) % 3;
    const double normal = (q[u] - p[u]) * (r[v] - p[v]) - (q[v] - p[v]) * (r[u] - p[u]);
    if ((bit & 1) ? normal > 0.0 : normal < 0.0) return bit;
  }
  return -1;
}

namespace {

// The triangles of `source` that `index` (the same surface in index coordinates) does not show
// as caps, with their points renumbered.
SurfaceMesh keep_non_caps(const SurfaceMesh& source, const SurfaceMesh& index, const volume::Index3& shape) {
  SurfaceMesh out;
  std::vector<std::uint32_t> number(source.points.size(), UINT32_MAX);
  for (std::size_t n = 0; n < source.triangles.size(); ++n) {
    if (cap_face(index, index.triangles[n], shape) >= 0) continue;
    Triangle t = source.triangles[n];
    for (std::uint32_t& v : t) {
      if (number[v] == UINT32_MAX) {
        number[v] = static_cast<std::uint32_t>(out.points.size());
        out.points.push_back(source.points[v]);
      }
      v = number[v];
    }
    out.triangles.push_back(t);
  }
  return out;
}

} // namespace

SurfaceMesh without_caps(const SurfaceMesh& s, const volume::Index3& shape) {
  return keep_non_caps(s, s, shape);
}

SurfaceMesh without_world_caps(const SurfaceMesh& world, const volume::Geometry& geometry) {
  const auto& f = geometry.affine;
  const double det = f.xi * f.yj - f.xj * f.yi;
  if (!(std::abs(det * geometry.dz) > 0.0) || !std::isfinite(det * geometry.dz))
    throw InvalidArgument("cannot find the caps of a surface: the survey affine and sample interval are degenerate", {},
                          "check the geometry's affine (xi, xj, yi, yj) and dz");
  SurfaceMesh index;
  index.points.reserve(world.points.size());
  for (const Point& p : world.points) {
    const double x = p[0] - f.x0, y = p[1] - f.y0;
    index.points.push_back(
        {(f.yj * x - f.xj * y) / det, (f.xi * y - f.yi * x) / det, (p[2] - geometry.z0) / geometry.dz});
  }
  index.triangles = world.triangles;
  // to_world swapped two corners when the map mirrors: swap back to see index-space orientation.
  if (det * geometry.dz < 0.0)
    for (Triangle& t : index.triangles)
      std::swap(t[1], t[2]);
  return keep_non_caps(world, index, geometry.shape);
}

std::string cut_faces_text(std::uint8_t faces) {
  std::string out;
  for (int bit = 0; bit < 6; ++bit)
    if ((faces >> bit) & 1u) {
      if (!out.empty()) out += ',';
      out += kFaceNames[bit];
    }
  return out;
}

std::uint8_t parse_cut_faces(const std::string& text) {
  std::uint8_t faces = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string name = text.substr(start, end - start);
    int bit = 0;
    while (bit < 6 && name != kFaceNames[bit])
      ++bit;
    if (bit == 6)
      throw InvalidArgument("unknown cube face '" + name + "' in cut faces '" + text + "'", {},
                            "name faces as i-, i+, j-, j+, k-, k+, separated by commas");
    faces |= static_cast<std::uint8_t>(1u << bit);
    start = end + 1;
  }
  return faces;
}

} // namespace geotandem::mesh
