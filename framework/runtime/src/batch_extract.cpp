// A batch spanning finished leaves, both ends (batch_extract.hpp).
#include "batch_extract.hpp"

#include <algorithm>
#include <cstring>
#include <string>

#include "byte_stream.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/runtime/aggregate.hpp"
#include "geotandem/tandem/blocks.hpp"
#include "geotandem/tandem/serialize.hpp"

namespace geotandem::runtime::detail {

using tandem::NodeId;

LeafRuns finished_runs(const tandem::BlockTree& tree, const Schedule& schedule, NodeId node) {
  LeafRuns runs;
  std::uint32_t ordinal = 0;
  for (NodeId n = node, end = subtree_end(tree, node); n < end; ++n) {
    if (!tree.node(n).is_leaf()) continue;
    if (schedule.finished(n)) {
      if (!runs.empty() && runs.back().first + runs.back().second == ordinal)
        ++runs.back().second;
      else
        runs.emplace_back(ordinal, 1);
    }
    ++ordinal;
  }
  return runs;
}

std::vector<std::byte> encode_runs(const LeafRuns& runs) {
  ByteWriter w;
  for (const auto& [first, count] : runs) {
    w.put(first);
    w.put(count);
  }
  return std::move(w.bytes());
}

LeafRuns decode_runs(std::span<const std::byte> bytes) {
  if (bytes.size() % 8 != 0)
    throw ProtocolError("EXTRACT: " + std::to_string(bytes.size()) +
                        " bytes of finished leaves, not whole (first, count) pairs of u32");
  LeafRuns runs;
  ByteReader r(bytes);
  while (!r.done()) {
    const auto first = r.get<std::uint32_t>("a run's first leaf");
    runs.emplace_back(first, r.get<std::uint32_t>("a run's leaves"));
  }
  return runs;
}

namespace {

using tandem::WorkingSurface;

class SkippingDriver {
public:
  SkippingDriver(const volume::Volume& volume, const tandem::BlockTree& tree, const std::vector<char>& skip,
                 const tandem::TandemOptions& options, mesh::ComponentSink* sink, bool brute)
      : volume_(volume), tree_(tree), options_(options), sink_(sink), brute_(brute), skipped_(tree.size(), 0) {
    // Per node: its leaves and those skipped, from the leaves up (ids put a parent before its children).
    std::size_t k = 0;
    for (NodeId leaf : tree.leaves())
      skipped_[static_cast<std::size_t>(leaf)] = skip[k++] != 0 ? 1 : 0;
    leaves_.assign(tree.size(), 1);
    for (std::size_t i = tree.size(); i-- > 0;) {
      const tandem::BlockNode& n = tree.node(static_cast<NodeId>(i));
      if (n.is_leaf()) continue;
      const auto low = static_cast<std::size_t>(n.children[0]), high = static_cast<std::size_t>(n.children[1]);
      skipped_[i] = skipped_[low] + skipped_[high];
      leaves_[i] = leaves_[low] + leaves_[high];
    }
  }

  // As tandem's block driver (blocks_driver.cpp): a subtree with nothing skipped in one call, else
  // its two sides, the smaller travelling to the other through its wire form. A side whose leaves
  // are all skipped is no surface.
  std::unique_ptr<WorkingSurface> run(NodeId id) {
    const auto i = static_cast<std::size_t>(id);
    if (skipped_[i] == leaves_[i]) return nullptr;
    const tandem::BlockNode& node = tree_.node(id);
    if (skipped_[i] == 0) {
      if (!node.is_leaf())
        return tandem::extract_subtree(volume_, node.cells, tree_.leaf_size(), options_, sink_, brute_);
      std::unique_ptr<WorkingSurface> surface;
      tandem::extract_block(volume_, node.cells, options_, sink_, &surface, brute_);
      return surface;
    }
    std::unique_ptr<WorkingSurface> low = run(node.children[0]);
    if (low) low->compact(); // set aside while its brother is extracted
    std::unique_ptr<WorkingSurface> high = run(node.children[1]);
    if (!low || !high) return low ? std::move(low) : std::move(high);
    const bool low_travels = low->triangle_count() < high->triangle_count();
    std::unique_ptr<WorkingSurface>& sent = low_travels ? low : high;
    std::unique_ptr<WorkingSurface>& kept = low_travels ? high : low;
    if (options_.cancel) options_.cancel->throw_if_cancelled();
    std::vector<std::byte> record = tandem::serialize(std::move(*sent));
    sent.reset();
    tandem::merge_record(*kept, std::move(record), options_.cancel);
    return std::move(kept);
  }

private:
  const volume::Volume& volume_;
  const tandem::BlockTree& tree_;
  const tandem::TandemOptions& options_;
  mesh::ComponentSink* sink_;
  bool brute_;
  std::vector<std::uint32_t> skipped_, leaves_;
};

} // namespace

std::unique_ptr<tandem::WorkingSurface> extract_batch(const volume::Volume& volume, const volume::Box& cells,
                                                      std::int64_t leaf, const LeafRuns& skip,
                                                      const tandem::TandemOptions& options, mesh::ComponentSink* sink,
                                                      bool brute) {
  const bool one_leaf = cells.size(0) <= leaf && cells.size(1) <= leaf && cells.size(2) <= leaf;
  if (skip.empty()) {
    if (!one_leaf) return tandem::extract_subtree(volume, cells, leaf, options, sink, brute);
    std::unique_ptr<tandem::WorkingSurface> surface;
    tandem::extract_block(volume, cells, options, sink, &surface, brute);
    return surface;
  }
  // The batch's subtree is the block tree of its cells (the split is local: block_tree.hpp).
  const tandem::BlockTree tree(cells, leaf);
  std::vector<char> skipped(tree.leaves().size(), 0);
  for (const auto& [first, count] : skip) {
    if (count == 0 || std::uint64_t{first} + count > skipped.size())
      throw InvalidArgument("EXTRACT of " + cells.to_string() + ": finished leaves " + std::to_string(first) + " to " +
                                std::to_string(std::uint64_t{first} + count) + " of a batch of " +
                                std::to_string(skipped.size()) + " leaves",
                            {.block = cells.to_string()},
                            "the manager and this worker split the cube differently: run the same geotandem "
                            "version on the manager and every worker");
    std::fill_n(skipped.begin() + first, count, char{1});
  }
  SkippingDriver driver(volume, tree, skipped, options, sink, brute);
  return driver.run(tree.root());
}

} // namespace geotandem::runtime::detail
