#pragma once
// Placing bodies: separation by index-space boxes, the roles special bodies play (crossing the
// block planes, cut by the border), and the flags and numbers of the ground truth.

#include <string>
#include <unordered_map>
#include <vector>

#include "frame.hpp"
#include "geotandem/synth/ground_truth.hpp"
#include "hash.hpp"

namespace geotandem::synth::detail {

// Keeps the boxes of the bodies placed so far; a new body is accepted when its box, grown by the
// gaps, overlaps none of them. Two accepted bodies are then at least `gap` samples apart along
// some axis.
class Packer {
public:
  Packer(const volume::Index3& shape, double gap_horizontal, double gap_vertical);
  bool fits(const Aabb& box) const;
  void add(const Aabb& box);
  // True when `box` comes within the gaps of a placed body.
  bool near_any(const Aabb& box) const { return !fits(box); }

private:
  std::int64_t cell_key(std::int64_t ci, std::int64_t cj, std::int64_t ck) const;
  template <class F> void for_cells(const Aabb& box, F&& f) const;

  volume::Index3 shape_;
  double gap_h_, gap_v_;
  std::vector<Aabb> boxes_;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> cells_;
};

// Where a body must go.
enum class Role {
  free,          // anywhere inside the cube, two samples from the border at least
  centre,        // near the crossing of the three mid-planes
  quarter_plane, // centred on the inline quarter-plane (1/4 or 3/4), crossing it
  border,        // centre just inside a face, the body cut by it
};

// A centre for `role` in index coordinates, drawn from `rng`; `half` are the body's index half
// extents, used to keep free bodies inside.
std::array<double, 3> draw_centre(LayoutRng& rng, Role role, const volume::Index3& shape,
                                  const std::array<double, 3>& half);

// True when `box` satisfies `role` (inside with a margin, or cut by the border for Role::border).
bool role_satisfied(Role role, const Aabb& box, const std::array<double, 3>& centre, const volume::Index3& shape);

// Sample indices of the planes at 1/4, 1/2 and 3/4 of an axis.
std::array<std::vector<std::int64_t>, 3> block_planes(const volume::Index3& shape);

// Fills the frame-derived fields of a body (centre, azimuth, volumes, bounds, border and plane
// flags).
Body describe_body(const Frame& frame, std::string name, BodyType type, const Vec3& centre, double azimuth_rad,
                   double volume_voxels, const Aabb& bounds);

// Sets the geometry fields of a ground truth from the frame.
void describe_frame(GroundTruth& truth, const Frame& frame);

// The special bodies of a layout, with the generator and the packer as their round left them (the
// filler bodies are drawn from them next).
template <class Candidate> struct SpecialBodies {
  std::vector<Candidate> placed;
  LayoutRng rng;
  Packer packer;
};

// Every special body must find room. `place_round(rng, packer, placed)` draws all `wanted` of them
// from its generator into its packer (empty at the start) and appends those that found room. When
// one cannot, the layout starts again from another deterministic stream of `layout_key` (small
// cubes may need a few rounds); after 16 rounds the first round that placed the most is kept.
template <class Candidate, class PlaceRound>
SpecialBodies<Candidate> place_special_bodies(std::uint64_t layout_key, std::size_t wanted, const Packer& empty,
                                              PlaceRound&& place_round) {
  constexpr std::int64_t rounds = 16;
  SpecialBodies<Candidate> best{{}, LayoutRng(layout_key), empty};
  for (std::int64_t round = 0; round < rounds; ++round) {
    SpecialBodies<Candidate> next{{}, LayoutRng(hash1(layout_key, round)), empty};
    place_round(next.rng, next.packer, next.placed);
    if (round == 0 || next.placed.size() > best.placed.size()) best = std::move(next);
    if (best.placed.size() == wanted) break;
  }
  return best;
}

} // namespace geotandem::synth::detail
