#pragma once
// Real working-surface records for the surface-record fuzz target: partial surfaces of a small
// analytic cube (geotandem synth's, 40^3 samples) cut into leaves of 16 cells, extracted as a
// worker extracts them. The target merges its inputs into the first leaf's surface; the seeds are
// the other leaves' records and the records of leaves merged together (several blocks).
#include <cstddef>
#include <memory>
#include <vector>

#include "geotandem/synth/synthetic.hpp"
#include "geotandem/tandem/block_tree.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "geotandem/tandem/serialize.hpp"
#include "geotandem/tandem/tandem.hpp"

namespace geotandem::fuzz {

struct SurfaceRecords {
  std::vector<std::byte> receiver;             // the first leaf's surface
  std::vector<std::vector<std::byte>> records; // the seeds
};

inline SurfaceRecords surface_records() {
  synth::AnalyticOptions cube;
  cube.shape = {40, 40, 40};
  const auto volume = synth::make_analytic(cube);
  tandem::TandemOptions options;
  options.iso = static_cast<float>(synth::analytic_iso);
  const tandem::BlockTree tree(tandem::cube_cells(cube.shape), 16);
  SurfaceRecords out;
  std::unique_ptr<tandem::WorkingSurface> fold;
  const std::vector<tandem::NodeId> leaves = tree.leaves();
  for (std::size_t k = 0; k < leaves.size(); ++k) {
    std::unique_ptr<tandem::WorkingSurface> piece;
    tandem::extract_block(*volume, tree.node(leaves[k]).cells, options, nullptr, &piece);
    if (out.receiver.empty()) {
      out.receiver = tandem::serialize(*piece);
      continue;
    }
    // About twenty seeds (the driver tries each seed first, unbounded by its time): the leaves
    // next to the receiver's, one leaf in eight, and the fold of the others every eight leaves.
    const std::vector<std::byte> record = tandem::serialize(*piece);
    if (k < 4 || k % 8 == 0) out.records.push_back(record);
    if (!fold)
      fold = std::move(piece);
    else
      tandem::merge_record(*fold, record);
    if (k % 8 == 7) out.records.push_back(tandem::serialize(*fold));
  }
  return out;
}

} // namespace geotandem::fuzz
