#pragma once
// The block-parallel route of the seed (section 3.2), run in one process: the cube's cells split
// into a binary block tree, each leaf extracted with the tandem loop (extract_block), brother
// surfaces merged bottom-up in tree order (WorkingSurface::merge), and the root finished. Before
// each merge the smaller of the two brothers travels through its wire form (serialize.hpp), as it
// will between the workers of the manager/worker runtime.
//
// The same components come out whatever the leaf size (the same keys; volumes and quality within
// the simplification's tolerance): the extended time lag keeps every vertex a neighbour welds to,
// and the seam is simplified once both sides are there.

#include <cstdint>
#include <memory>

#include "geotandem/mesh/component.hpp"
#include "geotandem/tandem/simplify.hpp"
#include "geotandem/tandem/tandem.hpp"
#include "geotandem/volume/box.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::tandem {

struct BlocksStats {
  // The layers of every leaf in tree order; final_pass: the root's finish(); counters: the totals
  // over every block and merge; peak_triangles: the most triangles one working surface held at a
  // layer boundary or after a merge; remaining_triangles: held at the end (0 for the whole cube).
  TandemStats tandem;
  std::size_t leaves = 0;
  std::size_t merges = 0;
  std::uint64_t seam_collapses = 0;       // collapses made by the merges (the seams)
  std::uint64_t components_at_merges = 0; // components finished by a merge or the final pass
  // Triangles held by all partial surfaces waiting for their brother, plus the one being built,
  // at most (the memory of the sequential route).
  std::uint64_t peak_held_triangles = 0;
  std::uint64_t wire_bytes = 0;     // sum of the records shipped
  std::uint64_t largest_record = 0; // bytes
  double seconds_leaves = 0.0;      // extract_block of every leaf
  double seconds_wire = 0.0;        // serialize + deserialize
  double seconds_merge = 0.0;       // merges (weld, seam simplification, dumping) and finish
};

// The leaves of `cells` (a node of the block tree of leaf size `block_size`: its subtree is the
// block tree of `cells`, the split being local) extracted and merged bottom-up as extract_blocks
// does, without the final pass: the surface stays open for later merges (a worker's batch of small
// leaves, issue 55). Finished components go to `sink` as they are found.
std::unique_ptr<WorkingSurface> extract_subtree(const volume::Volume& volume, const volume::Box& cells,
                                                std::int64_t block_size, const TandemOptions& options,
                                                mesh::ComponentSink* sink, bool brute = false);

// Extracts the isosurface of `cells` (a box of cells of the volume's cube, usually
// cube_cells(shape)) with a block tree of leaf size `block_size` cells (<= 0: one block), finished
// components to `sink` (may be null). options.progress (may be null) sees one task, one unit per
// layer of every leaf and per merge; options.cancel is checked between layers and merges.
// `brute`: each leaf by brute force (extract, then simplify) instead of the tandem.
// `remaining` (may be null) receives the root's surface: empty when `cells` is the whole cube,
// otherwise what touches the faces of `cells` inside the cube.
// Throws InvalidArgument on invalid options or cells outside the cube, what the volume throws,
// and Cancelled.
BlocksStats extract_blocks(const volume::Volume& volume, const volume::Box& cells, std::int64_t block_size,
                           const TandemOptions& options, mesh::ComponentSink* sink,
                           std::unique_ptr<WorkingSurface>* remaining = nullptr, bool brute = false);

} // namespace geotandem::tandem
