#pragma once
// Fixtures for the marching-cubes tests: fields from formulas, a volume that records its reads,
// and small independent oracles (enclosed volume, welding, triangle sets, voxel components).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "geotandem/mesh/surface.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::tandem::testing {

using volume::Box;
using volume::Index3;

inline volume::Geometry geometry_of(const Index3& shape) {
  volume::Geometry g;
  g.shape = shape;
  return g;
}

// A memory volume sampled from f(i, j, k).
inline std::unique_ptr<volume::MemoryVolume> field(const Index3& shape,
                                                   const std::function<float(double, double, double)>& f) {
  std::vector<float> samples(static_cast<std::size_t>(shape[0] * shape[1] * shape[2]));
  std::size_t n = 0;
  for (std::int64_t i = 0; i < shape[0]; ++i)
    for (std::int64_t j = 0; j < shape[1]; ++j)
      for (std::int64_t k = 0; k < shape[2]; ++k)
        samples[n++] = f(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k));
  return std::make_unique<volume::MemoryVolume>(geometry_of(shape), std::move(samples), "test field");
}

// Positive inside a sphere of radius r centred at c.
inline std::function<float(double, double, double)> sphere(std::array<double, 3> c, double r) {
  return [c, r](double i, double j, double k) {
    return static_cast<float>(r -
                              std::sqrt((i - c[0]) * (i - c[0]) + (j - c[1]) * (j - c[1]) + (k - c[2]) * (k - c[2])));
  };
}

// Positive inside a torus around the k axis through c (major radius R, minor radius r).
inline std::function<float(double, double, double)> torus(std::array<double, 3> c, double R, double r) {
  return [c, R, r](double i, double j, double k) {
    const double q = std::sqrt((i - c[0]) * (i - c[0]) + (j - c[1]) * (j - c[1])) - R;
    return static_cast<float>(r - std::sqrt(q * q + (k - c[2]) * (k - c[2])));
  };
}

// Random values in [-1, 1] (with `levels` > 0: integers in [0, levels)), and `outside` on the
// cube's outer shell so that the surface closes.
inline std::unique_ptr<volume::MemoryVolume> noise(const Index3& shape, unsigned seed, int levels = 0,
                                                   float outside = -1.0f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> real(-1.0f, 1.0f);
  std::uniform_int_distribution<int> integer(0, std::max(levels, 1) - 1);
  return field(shape, [&](double i, double j, double k) {
    const float x = levels > 0 ? static_cast<float>(integer(rng)) : real(rng);
    const bool shell = i == 0 || j == 0 || k == 0 || i == shape[0] - 1 || j == shape[1] - 1 || k == shape[2] - 1;
    return shell ? outside : x;
  });
}

// Signed enclosed volume by the divergence theorem.
inline double enclosed_volume(const mesh::SurfaceMesh& s) {
  double v = 0;
  for (const auto& t : s.triangles) {
    const auto& a = s.points[t[0]];
    const auto& b = s.points[t[1]];
    const auto& c = s.points[t[2]];
    v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return v / 6.0;
}

// A triangle as its three vertex ids, rotated so that the smallest id comes first (orientation kept).
using IdTriangle = std::array<std::uint64_t, 3>;
inline IdTriangle canonical(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  if (b < a && b < c) return {b, c, a};
  if (c < a && c < b) return {c, a, b};
  return {a, b, c};
}

// The surface as a multiset of id triangles plus the position of every id.
struct IdSurface {
  std::multiset<IdTriangle> triangles;
  std::map<std::uint64_t, std::array<double, 3>> positions;
  bool positions_agree = true; // false when one id was seen with two different positions
};

inline void add_to(IdSurface& out, const mesh::SurfaceMesh& s, const std::vector<std::uint64_t>& ids) {
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const auto [it, inserted] = out.positions.emplace(ids[i], s.points[i]);
    if (!inserted && it->second != s.points[i]) out.positions_agree = false;
  }
  for (const auto& t : s.triangles)
    out.triangles.insert(canonical(ids[t[0]], ids[t[1]], ids[t[2]]));
}

// Welds an IdSurface into a mesh (vertices numbered in id order).
inline mesh::SurfaceMesh to_mesh(const IdSurface& s) {
  mesh::SurfaceMesh m;
  std::map<std::uint64_t, std::uint32_t> index;
  for (const auto& [id, p] : s.positions) {
    index[id] = static_cast<std::uint32_t>(m.points.size());
    m.points.push_back(p);
  }
  for (const auto& t : s.triangles)
    m.triangles.push_back({index.at(t[0]), index.at(t[1]), index.at(t[2])});
  return m;
}

// A volume that forwards to another and records every box it was asked for.
class RecordingVolume final : public volume::Volume {
public:
  explicit RecordingVolume(const volume::Volume& inner, Index3 halo = {0, 0, 0}) : inner_(inner), halo_(halo) {}
  const volume::Geometry& geometry() const override { return inner_.geometry(); }
  Index3 source_halo() const override { return halo_; } // as a computed volume would declare
  std::string format() const override { return "recording"; }
  std::string source() const override { return "recording(" + inner_.source() + ")"; }
  const std::vector<Box>& reads() const { return reads_; }

protected:
  void read_box(const Box& box, std::span<float> out) const override {
    reads_.push_back(box);
    inner_.read(box, out);
  }

private:
  const volume::Volume& inner_;
  Index3 halo_;
  mutable std::vector<Box> reads_;
};

// Number of distinct (inside 6-component, outside 18-component) pairs that touch along a lattice
// edge: with inside corners of ambiguous faces separated, the inside is 6-connected and the
// outside 18-connected, and each such pair is bounded by one connected surface component.
inline std::size_t boundary_pairs(const volume::MemoryVolume& v, float iso) {
  const Index3 n = v.geometry().shape;
  const auto& x = v.samples();
  std::vector<std::size_t> parent(x.size());
  for (std::size_t i = 0; i < parent.size(); ++i)
    parent[i] = i;
  auto find = [&](std::size_t a) {
    while (parent[a] != a)
      a = parent[a] = parent[parent[a]];
    return a;
  };
  auto at = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    return static_cast<std::size_t>((i * n[1] + j) * n[2] + k);
  };
  auto in = [&](std::size_t s) { return x[s] >= iso; };
  for (std::int64_t i = 0; i < n[0]; ++i)
    for (std::int64_t j = 0; j < n[1]; ++j)
      for (std::int64_t k = 0; k < n[2]; ++k)
        for (int di = -1; di <= 1; ++di)
          for (int dj = -1; dj <= 1; ++dj)
            for (int dk = -1; dk <= 1; ++dk) {
              const int nonzero = (di != 0) + (dj != 0) + (dk != 0);
              const std::int64_t i2 = i + di, j2 = j + dj, k2 = k + dk;
              if (nonzero == 0 || nonzero == 3 || i2 < 0 || j2 < 0 || k2 < 0 || i2 >= n[0] || j2 >= n[1] || k2 >= n[2])
                continue;
              const std::size_t a = at(i, j, k), b = at(i2, j2, k2);
              if (in(a) != in(b) || (in(a) && nonzero != 1)) continue;
              parent[find(a)] = find(b);
            }
  std::set<std::pair<std::size_t, std::size_t>> pairs;
  for (std::int64_t i = 0; i < n[0]; ++i)
    for (std::int64_t j = 0; j < n[1]; ++j)
      for (std::int64_t k = 0; k < n[2]; ++k)
        for (int axis = 0; axis < 3; ++axis) {
          Index3 q{i, j, k};
          if (++q[axis] >= n[axis]) continue;
          const std::size_t a = at(i, j, k), b = at(q[0], q[1], q[2]);
          if (in(a) == in(b)) continue;
          pairs.emplace(find(in(a) ? a : b), find(in(a) ? b : a));
        }
  return pairs.size();
}

} // namespace geotandem::tandem::testing
