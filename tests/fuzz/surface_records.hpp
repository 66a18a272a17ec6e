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
  for (tandem::NodeId leaf : tree.leaves()) {
    std::unique_ptr<tandem::WorkingSurface> piece;
    tandem::extract_block(*volume, tree.node(leaf).cells, options, nullptr, &piece);
    if (out.receiver.empty()) {
      out.receiver = tandem::serialize(*piece);
      continue;
    }
    out.records.push_back(tandem::serialize(*piece));
    if (!fold)
      fold = std::move(piece);
    else
      tandem::merge_record(*fold, tandem::serialize(*piece));
    if (out.records.size() % 3 == 0) out.records.push_back(tandem::serialize(*fold));
  }
  return out;
}

} // namespace geotandem::fuzz
