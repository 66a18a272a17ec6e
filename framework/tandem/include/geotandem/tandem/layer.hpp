#pragma once
// What marching cubes hands to the simplifier for one layer: the triangles between two
// cross-sections, with every vertex named by the global id of the lattice edge it was born on.

#include <array>
#include <cstdint>
#include <vector>

#include "geotandem/volume/box.hpp"

namespace geotandem::tandem {

// Global lattice-edge ids over the whole cube's grid (shape ni x nj x nk of samples):
//   id = 3 * ((i * nj + j) * nk + k) + axis,
// for the edge that starts at sample (i, j, k) and goes one step along `axis` (0 = i, 1 = j,
// 2 = k). 64 bits; the same edge has the same id whichever block sees it.
struct LatticeIds {
  volume::Index3 shape{0, 0, 0};
  std::uint64_t id(std::int64_t i, std::int64_t j, std::int64_t k, int axis) const {
    return 3u *
               ((static_cast<std::uint64_t>(i) * static_cast<std::uint64_t>(shape[1]) + static_cast<std::uint64_t>(j)) *
                    static_cast<std::uint64_t>(shape[2]) +
                static_cast<std::uint64_t>(k)) +
           static_cast<std::uint64_t>(axis);
  }
  // Cap vertices sit on samples of the cube's outer planes: their ids follow every edge id,
  //   id = 3 * ni * nj * nk + (i * nj + j) * nk + k,
  // so they never decide a component's key while it has an edge vertex.
  std::uint64_t sample_id(std::int64_t i, std::int64_t j, std::int64_t k) const {
    const auto n = static_cast<std::uint64_t>(shape[0]) * static_cast<std::uint64_t>(shape[1]) *
                   static_cast<std::uint64_t>(shape[2]);
    return 3u * n + (id(i, j, k, 0) / 3u);
  }
  bool is_sample(std::uint64_t id) const {
    return id / 3u >= static_cast<std::uint64_t>(shape[0]) * static_cast<std::uint64_t>(shape[1]) *
                          static_cast<std::uint64_t>(shape[2]);
  }
  // The start sample and axis of an edge id.
  volume::Index3 start(std::uint64_t id) const;
  int axis(std::uint64_t id) const { return static_cast<int>(id % 3u); }
};

// One layer k: every cell between cross-sections k-1 and k (along the extraction axis) of a block.
// Vertices are listed once per layer, including those on cross-section k-1 that the previous
// layer already produced (the consumer keeps the first copy; positions are bit-identical).
struct Layer {
  int axis = 0;                                        // extraction axis (0, 1 or 2)
  std::int64_t rank = 0;                               // k: the cross-section this layer ends on (global index)
  std::vector<std::uint64_t> vertex_ids;               // lattice-edge id per vertex
  std::vector<std::array<double, 3>> positions;        // index coordinates (i, j, k) per vertex
  std::vector<std::array<std::uint32_t, 3>> triangles; // into vertex_ids/positions, oriented outward
  // Per vertex, its share of the enclosed samples (issue 54): a vertex on a crossed edge along the
  // sample axis (k, k + 1) counts k + 1 when sample k is inside (a run of inside samples ends) and
  // -(k + 1) when sample k + 1 is (a run starts); a cap vertex on the last sample plane counts nk;
  // every other vertex 0. Summed over a closed surface: the samples it encloses (discrete
  // divergence theorem along the traces). Empty: all 0 (sources that do not count).
  std::vector<std::int64_t> vertex_samples;

  void clear() {
    vertex_samples.clear();
    vertex_ids.clear();
    positions.clear();
    triangles.clear();
  }
};

} // namespace geotandem::tandem
