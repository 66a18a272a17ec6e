#include "simplify_fixtures.hpp"

#include "geotandem/tandem/marching_cubes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>

namespace geotandem::tandem::fixtures {

Field sphere(std::array<double, 3> c, double r) {
  return [c, r](double i, double j, double k) {
    return r - std::sqrt((i - c[0]) * (i - c[0]) + (j - c[1]) * (j - c[1]) + (k - c[2]) * (k - c[2]));
  };
}

Field ellipsoid(std::array<double, 3> c, std::array<double, 3> r) {
  return [c, r](double i, double j, double k) {
    const double x = (i - c[0]) / r[0], y = (j - c[1]) / r[1], z = (k - c[2]) / r[2];
    // Scaled by the smallest radius so that the field is roughly a distance near the surface.
    return 0.5 * std::min({r[0], r[1], r[2]}) * (1.0 - (x * x + y * y + z * z));
  };
}

Field torus(std::array<double, 3> c, double major, double minor) {
  return [c, major, minor](double i, double j, double k) {
    const double x = i - c[0], y = j - c[1], z = k - c[2];
    const double q = std::sqrt(x * x + y * y) - major;
    return minor - std::sqrt(q * q + z * z);
  };
}

Field union_of(std::vector<Field> fields) {
  return [fields = std::move(fields)](double i, double j, double k) {
    double best = -std::numeric_limits<double>::infinity();
    for (const Field& f : fields)
      best = std::max(best, f(i, j, k));
    return best;
  };
}

volume::Geometry test_geometry(const volume::Index3& shape) {
  volume::Geometry g;
  g.shape = shape;
  return g;
}

namespace {

constexpr double kMargin = 1.0 / 256.0;

struct Sample {
  std::array<std::int64_t, 3> p;
};

// Emits the triangles of one cell into `out` (positions and ids per corner).
struct CellMesher {
  const std::vector<double>& values;
  const volume::Box& samples;
  const volume::Index3& shape;
  double iso;

  std::uint64_t id(const std::array<std::int64_t, 3>& lo, unsigned dir) const {
    const auto lin =
        (static_cast<std::uint64_t>(lo[0]) * static_cast<std::uint64_t>(shape[1]) + static_cast<std::uint64_t>(lo[1])) *
            static_cast<std::uint64_t>(shape[2]) +
        static_cast<std::uint64_t>(lo[2]);
    return 7u * lin + (dir - 1u);
  }
  double value(const std::array<std::int64_t, 3>& s) const { return values[samples.offset(s)]; }

  // The vertex on the segment between two corners of a tetrahedron (one inside, one outside).
  void vertex(const std::array<std::int64_t, 3>& u, const std::array<std::int64_t, 3>& w, double fu, double fw,
              std::uint64_t& vid, std::array<double, 3>& pos) const {
    // Interpolate from the lower corner, like marching cubes, so every cell computes the same.
    const bool u_low = u[0] <= w[0] && u[1] <= w[1] && u[2] <= w[2];
    const auto& lo = u_low ? u : w;
    const auto& hi = u_low ? w : u;
    const double flo = u_low ? fu : fw, fhi = u_low ? fw : fu;
    unsigned dir = 0;
    for (unsigned a = 0; a < 3; ++a)
      if (hi[a] != lo[a]) dir |= 1u << a;
    double t = (iso - flo) / (fhi - flo);
    t = std::clamp(t, kMargin, 1.0 - kMargin);
    vid = id(lo, dir);
    for (unsigned a = 0; a < 3; ++a)
      pos[a] = static_cast<double>(lo[a]) + t * static_cast<double>(hi[a] - lo[a]);
  }

  template <class Emit> void cell(const std::array<std::int64_t, 3>& c, Emit&& emit) const {
    static constexpr int kPerms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (const auto& perm : kPerms) {
      std::array<std::array<std::int64_t, 3>, 4> v;
      v[0] = c;
      v[1] = v[0];
      v[1][static_cast<std::size_t>(perm[0])] += 1;
      v[2] = v[1];
      v[2][static_cast<std::size_t>(perm[1])] += 1;
      v[3] = {c[0] + 1, c[1] + 1, c[2] + 1};
      // Positive orientation: det(v1 - v0, v2 - v0, v3 - v0) > 0, else swap v2 and v3.
      auto d = [&](int i, int a) {
        return static_cast<double>(v[static_cast<std::size_t>(i)][static_cast<std::size_t>(a)] -
                                   v[0][static_cast<std::size_t>(a)]);
      };
      const double det = d(1, 0) * (d(2, 1) * d(3, 2) - d(2, 2) * d(3, 1)) -
                         d(1, 1) * (d(2, 0) * d(3, 2) - d(2, 2) * d(3, 0)) +
                         d(1, 2) * (d(2, 0) * d(3, 1) - d(2, 1) * d(3, 0));
      if (det < 0) std::swap(v[2], v[3]);
      double f[4];
      bool in[4];
      int inside = 0;
      for (int i = 0; i < 4; ++i) {
        f[i] = value(v[static_cast<std::size_t>(i)]);
        in[i] = f[i] >= iso;
        inside += in[i] ? 1 : 0;
      }
      if (inside == 0 || inside == 4) continue;
      // Order the corners so that the first ones are the minority side, with an even permutation.
      int order[4], n = 0;
      const bool minority_inside = inside <= 2;
      for (int i = 0; i < 4; ++i)
        if (in[i] == minority_inside) order[n++] = i;
      const int split = n;
      for (int i = 0; i < 4; ++i)
        if (in[i] != minority_inside) order[n++] = i;
      int inversions = 0;
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
          inversions += order[i] > order[j] ? 1 : 0;
      if (inversions % 2) std::swap(order[2], order[3]);
      auto e = [&](int i, int j, std::uint64_t& vid, std::array<double, 3>& pos) {
        vertex(v[static_cast<std::size_t>(order[i])], v[static_cast<std::size_t>(order[j])], f[order[i]], f[order[j]],
               vid, pos);
      };
      std::uint64_t ids[4];
      std::array<double, 3> pos[4];
      if (split == 1 || split == 3) {
        // One corner apart: the triangle around it, facing away from it when it is inside.
        e(0, 1, ids[0], pos[0]);
        e(0, 2, ids[1], pos[1]);
        e(0, 3, ids[2], pos[2]);
        if (split == 1 && minority_inside)
          emit(ids[0], pos[0], ids[1], pos[1], ids[2], pos[2]);
        else
          emit(ids[0], pos[0], ids[2], pos[2], ids[1], pos[1]);
      } else {
        // Two and two: the quad (e02, e03, e13, e12), facing from the inside pair outwards.
        e(0, 2, ids[0], pos[0]);
        e(0, 3, ids[1], pos[1]);
        e(1, 3, ids[2], pos[2]);
        e(1, 2, ids[3], pos[3]);
        emit(ids[0], pos[0], ids[1], pos[1], ids[2], pos[2]);
        emit(ids[0], pos[0], ids[2], pos[2], ids[3], pos[3]);
      }
    }
  }
};

} // namespace

TetraLayers::TetraLayers(Field field, volume::Index3 shape, volume::Box cells, double iso, int axis)
    : samples_{cells.lo, {cells.hi[0] + 1, cells.hi[1] + 1, cells.hi[2] + 1}}, shape_(shape), cells_(cells), iso_(iso),
      axis_(axis), next_rank_(cells.lo[axis] + 1) {
  values_.resize(samples_.count());
  for (std::int64_t i = samples_.lo[0]; i < samples_.hi[0]; ++i)
    for (std::int64_t j = samples_.lo[1]; j < samples_.hi[1]; ++j)
      for (std::int64_t k = samples_.lo[2]; k < samples_.hi[2]; ++k)
        values_[samples_.offset({i, j, k})] =
            field(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k));
}

bool TetraLayers::next(Layer& layer) {
  layer.clear();
  if (next_rank_ > cells_.hi[axis_]) return false;
  layer.axis = axis_;
  layer.rank = next_rank_;
  const std::int64_t slab = next_rank_ - 1;
  ++next_rank_;
  std::unordered_map<std::uint64_t, std::uint32_t> index;
  auto vertex = [&](std::uint64_t id, const std::array<double, 3>& p) {
    auto [it, fresh] = index.emplace(id, static_cast<std::uint32_t>(layer.vertex_ids.size()));
    if (fresh) {
      layer.vertex_ids.push_back(id);
      layer.positions.push_back(p);
    }
    return it->second;
  };
  CellMesher mesher{values_, samples_, shape_, iso_};
  const int u = axis_ == 0 ? 1 : 0, w = axis_ == 2 ? 1 : 2;
  for (std::int64_t a = cells_.lo[u]; a < cells_.hi[u]; ++a)
    for (std::int64_t b = cells_.lo[w]; b < cells_.hi[w]; ++b) {
      std::array<std::int64_t, 3> c{};
      c[static_cast<std::size_t>(axis_)] = slab;
      c[static_cast<std::size_t>(u)] = a;
      c[static_cast<std::size_t>(w)] = b;
      mesher.cell(c, [&](std::uint64_t i0, const std::array<double, 3>& p0, std::uint64_t i1,
                         const std::array<double, 3>& p1, std::uint64_t i2, const std::array<double, 3>& p2) {
        layer.triangles.push_back({vertex(i0, p0), vertex(i1, p1), vertex(i2, p2)});
      });
    }
  return true;
}

mesh::SurfaceMesh tetra_surface(const Field& field, const volume::Index3& shape, const volume::Box& cells, double iso,
                                int axis, std::vector<std::uint64_t>* ids) {
  TetraLayers source(field, shape, cells, iso, axis);
  mesh::SurfaceMesh out;
  std::unordered_map<std::uint64_t, std::uint32_t> index;
  std::vector<std::uint64_t> all_ids;
  Layer layer;
  while (source.next(layer)) {
    std::vector<std::uint32_t> local(layer.vertex_ids.size());
    for (std::size_t i = 0; i < layer.vertex_ids.size(); ++i) {
      auto [it, fresh] = index.emplace(layer.vertex_ids[i], static_cast<std::uint32_t>(out.points.size()));
      if (fresh) {
        out.points.push_back(layer.positions[i]);
        all_ids.push_back(layer.vertex_ids[i]);
      }
      local[i] = it->second;
    }
    for (const auto& t : layer.triangles)
      out.triangles.push_back({local[t[0]], local[t[1]], local[t[2]]});
  }
  if (ids) *ids = std::move(all_ids);
  return out;
}

const char* to_string(Mesher m) {
  return m == Mesher::marching_cubes ? "marching cubes" : "marching tetrahedra";
}

Input::Input(Field field, volume::Index3 shape, Mesher mesher)
    : field_(std::move(field)), shape_(shape), mesher_(mesher) {
  if (mesher_ != Mesher::marching_cubes) return;
  const volume::Geometry g = test_geometry(shape_);
  std::vector<float> samples(g.bounds().count());
  for (std::int64_t i = 0; i < shape_[0]; ++i)
    for (std::int64_t j = 0; j < shape_[1]; ++j)
      for (std::int64_t k = 0; k < shape_[2]; ++k)
        samples[g.bounds().offset({i, j, k})] =
            static_cast<float>(field_(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k)));
  volume_ = std::make_unique<volume::MemoryVolume>(g, std::move(samples), "test field");
}

volume::Box Input::cells() const {
  return cube_cells(shape_);
}

std::unique_ptr<LayerSource> Input::layers(const volume::Box& cells, int axis) const {
  if (mesher_ == Mesher::tetrahedra) return std::make_unique<TetraLayers>(field_, shape_, cells, 0.0, axis);
  TandemOptions options;
  options.iso = 0.0f;
  options.axis = axis;
  return marching_cubes_source(*volume_, cells, options);
}

mesh::SurfaceMesh Input::full(const volume::Box& cells, int axis, std::vector<std::uint64_t>* ids) const {
  if (mesher_ == Mesher::tetrahedra) return tetra_surface(field_, shape_, cells, 0.0, axis, ids);
  return extract_surface(*volume_, cells, McOptions{0.0f, axis}, ids);
}

void CollectingSink::commit(const mesh::Component& component) {
  components.push_back(component);
  commit_front.push_back(surface ? static_cast<std::int64_t>(std::min(surface->front(), 1e18)) : 0);
}

mesh::SurfaceMesh concatenate(const std::vector<mesh::Component>& components) {
  mesh::SurfaceMesh out;
  for (const mesh::Component& c : components) {
    const auto base = static_cast<std::uint32_t>(out.points.size());
    out.points.insert(out.points.end(), c.surface.points.begin(), c.surface.points.end());
    for (const auto& t : c.surface.triangles)
      out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  return out;
}

} // namespace geotandem::tandem::fixtures
