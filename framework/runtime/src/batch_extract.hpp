#pragma once
// An EXTRACT's batch that spans finished leaves (issue 55; Schedule::set_batch): the manager names
// the finished leaves of the batch's subtree as runs of leaf ordinals (in tree order, within the
// subtree) in the message's bytes; the worker extracts the others and merges them bottom-up as
// tandem::extract_subtree does, the finished ones standing for empty surfaces. Internal to the
// runtime.
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "geotandem/mesh/component.hpp"
#include "geotandem/runtime/schedule.hpp"
#include "geotandem/tandem/block_tree.hpp"
#include "geotandem/tandem/tandem.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::runtime::detail {

// (first ordinal, count): consecutive leaves of a batch's subtree, in tree order.
using LeafRuns = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// The finished leaves of `node`'s subtree (Schedule::finished) as runs, and their wire form (u32
// pairs, little-endian; empty when none).
LeafRuns finished_runs(const tandem::BlockTree& tree, const Schedule& schedule, tandem::NodeId node);
std::vector<std::byte> encode_runs(const LeafRuns& runs);
// Throws ProtocolError when the bytes are not whole pairs.
LeafRuns decode_runs(std::span<const std::byte> bytes);

// The merges inside a batch, summed (the task log's columns; the scale model prices a SEND and a
// MERGE with them): the smaller side's leaves and record bytes, the time serialising those records
// and merging them; and the time merging the batch's surface into the worker's (absorb: 0 when the
// worker held nothing), a merge into a large surface as a MERGE is. A DONE of an EXTRACT carries
// them in its bytes (six u64: microseconds for the times); decode_merges gives zeros for no bytes,
// throws ProtocolError otherwise.
struct BatchMerges {
  std::uint64_t merges = 0, leaves = 0, bytes = 0;
  double wire_seconds = 0, merge_seconds = 0, absorb_seconds = 0;
};
std::vector<std::byte> encode_merges(const BatchMerges& m);
BatchMerges decode_merges(std::span<const std::byte> bytes);

// The surface of the leaves of `cells` (a node of the block tree of leaf size `leaf`) but those of
// `skip` (its leaves by ordinal, finished by an earlier task or run), extracted and merged
// bottom-up as tandem::extract_subtree does (the smaller of two brothers through its wire form);
// finished components to `sink`, the merges' figures added to `merges` (may be null). Null when
// every leaf is skipped. Throws InvalidArgument when a run
// leaves the subtree's leaves (the manager and the worker disagree on the tree: nothing is
// extracted), and what the tandem throws.
std::unique_ptr<tandem::WorkingSurface> extract_batch(const volume::Volume& volume, const volume::Box& cells,
                                                      std::int64_t leaf, const LeafRuns& skip,
                                                      const tandem::TandemOptions& options, mesh::ComponentSink* sink,
                                                      bool brute, BatchMerges* merges = nullptr);

} // namespace geotandem::runtime::detail
