#include "layout.hpp"

#include <algorithm>
#include <cmath>

namespace geotandem::synth::detail {
namespace {

constexpr double cell_size = 32.0;

// Free bodies keep this many samples between their box and the border, so that their isosurface
// is closed and their volume complete.
constexpr double border_margin = 2.0;

} // namespace

Packer::Packer(const volume::Index3& shape, double gap_horizontal, double gap_vertical)
    : shape_(shape), gap_h_(gap_horizontal), gap_v_(gap_vertical) {}

std::int64_t Packer::cell_key(std::int64_t ci, std::int64_t cj, std::int64_t ck) const {
  // Cells range over the cube plus a margin of a few cells on each side; offset to stay positive.
  constexpr std::int64_t span = 1 << 20;
  return ((ci + 64) * span + (cj + 64)) * span + (ck + 64);
}

template <class F> void Packer::for_cells(const Aabb& box, F&& f) const {
  std::int64_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    const double limit = static_cast<double>(shape_[a]) + 2.0 * cell_size;
    lo[a] = static_cast<std::int64_t>(std::floor(std::clamp(box.lo[a], -2.0 * cell_size, limit) / cell_size));
    hi[a] = static_cast<std::int64_t>(std::floor(std::clamp(box.hi[a], -2.0 * cell_size, limit) / cell_size));
  }
  for (std::int64_t ci = lo[0]; ci <= hi[0]; ++ci)
    for (std::int64_t cj = lo[1]; cj <= hi[1]; ++cj)
      for (std::int64_t ck = lo[2]; ck <= hi[2]; ++ck)
        if (!f(cell_key(ci, cj, ck))) return;
}

bool Packer::fits(const Aabb& box) const {
  const Aabb grown = box.grown(gap_h_, gap_v_);
  bool free = true;
  for_cells(grown, [&](std::int64_t key) {
    auto it = cells_.find(key);
    if (it == cells_.end()) return true;
    for (std::size_t n : it->second)
      if (boxes_[n].overlaps(grown)) {
        free = false;
        return false;
      }
    return true;
  });
  return free;
}

void Packer::add(const Aabb& box) {
  boxes_.push_back(box);
  for_cells(box, [&](std::int64_t key) {
    cells_[key].push_back(boxes_.size() - 1);
    return true;
  });
}

std::array<double, 3> draw_centre(LayoutRng& rng, Role role, const volume::Index3& shape,
                                  const std::array<double, 3>& half) {
  std::array<double, 3> c{};
  std::array<double, 3> n{};
  for (int a = 0; a < 3; ++a)
    n[a] = static_cast<double>(shape[a]);
  auto anywhere = [&](int a) {
    const double lo = border_margin + half[a], hi = n[a] - 1.0 - border_margin - half[a];
    return lo < hi ? rng.uniform(lo, hi) : 0.5 * (n[a] - 1.0);
  };
  switch (role) {
  case Role::free:
    for (int a = 0; a < 3; ++a)
      c[a] = anywhere(a);
    break;
  case Role::centre:
    // Off the sample grid so that no sample lies exactly on a symmetry plane of the body.
    for (int a = 0; a < 3; ++a)
      c[a] = std::floor(n[a] / 2.0) + rng.uniform(-1.5, 1.5);
    break;
  case Role::quarter_plane:
    c[0] = std::floor(n[0] * (rng.uniform(0.0, 1.0) < 0.5 ? 1.0 : 3.0) / 4.0) + rng.uniform(-1.0, 1.0);
    c[1] = anywhere(1);
    c[2] = anywhere(2);
    break;
  case Role::border: {
    for (int a = 0; a < 3; ++a)
      c[a] = anywhere(a);
    const int axis = static_cast<int>(rng.next() % 2); // a vertical face: inline or crossline
    const double depth = rng.uniform(1.0, 0.6 * half[axis]);
    c[axis] = rng.uniform(0.0, 1.0) < 0.5 ? depth : n[axis] - 1.0 - depth;
    break;
  }
  }
  return c;
}

bool role_satisfied(Role role, const Aabb& box, const std::array<double, 3>& centre, const volume::Index3& shape) {
  bool inside = true, cut = false;
  for (int a = 0; a < 3; ++a) {
    const double last = static_cast<double>(shape[a] - 1);
    inside = inside && box.lo[a] >= border_margin && box.hi[a] <= last - border_margin;
    cut = cut || box.lo[a] < -0.5 || box.hi[a] > last + 0.5;
    // A border body's centre stays inside so that the part in the cube is one solid piece.
    if (role == Role::border && (centre[a] < 1.0 || centre[a] > last - 1.0)) return false;
  }
  return role == Role::border ? cut : inside;
}

std::array<std::vector<std::int64_t>, 3> block_planes(const volume::Index3& shape) {
  std::array<std::vector<std::int64_t>, 3> planes;
  for (int a = 0; a < 3; ++a)
    for (std::int64_t m = 1; m <= 3; ++m)
      planes[a].push_back(shape[a] * m / 4);
  return planes;
}

Body describe_body(const Frame& frame, std::string name, BodyType type, const Vec3& centre, double azimuth_rad,
                   double volume_voxels, const Aabb& bounds) {
  const auto& shape = frame.geometry().shape;
  Body body;
  body.name = std::move(name);
  body.type = type;
  body.centre_index = frame.to_index(centre);
  body.centre_world = frame.world(centre);
  body.azimuth_deg = axial_degrees(azimuth_rad);
  body.volume_voxels = volume_voxels;
  body.volume_world = volume_voxels * frame.voxel_volume_world();
  body.bounds_lo = bounds.lo;
  body.bounds_hi = bounds.hi;
  auto planes = block_planes(shape);
  for (int a = 0; a < 3; ++a) {
    const double last = static_cast<double>(shape[a] - 1);
    if (bounds.lo[a] < 1.0 || bounds.hi[a] > last - 1.0) body.cut_by_border = true;
    for (auto p : planes[a])
      if (bounds.lo[a] < static_cast<double>(p) && bounds.hi[a] > static_cast<double>(p))
        body.crosses_block_plane = true;
  }
  return body;
}

void describe_frame(GroundTruth& truth, const Frame& frame) {
  truth.geometry = frame.geometry();
  truth.world_volume_unit = frame.geometry().z_unit == volume::SampleUnit::milliseconds ? "m2*ms" : "m3";
  truth.body_frame_unit_m = frame.unit_m();
  truth.voxel_volume_world = frame.voxel_volume_world();
  truth.block_planes = block_planes(frame.geometry().shape);
}

} // namespace geotandem::synth::detail
