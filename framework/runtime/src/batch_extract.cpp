// A batch spanning finished leaves, both ends (batch_extract.hpp).
#include "batch_extract.hpp"

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <string>

#include "byte_stream.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/runtime/aggregate.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
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

std::vector<std::byte> encode_merges(const BatchMerges& m) {
  if (m.merges == 0 && m.absorb_seconds <= 0) return {};
  ByteWriter w;
  w.put(m.merges);
  w.put(m.leaves);
  w.put(m.bytes);
  w.put(static_cast<std::uint64_t>(m.wire_seconds * 1e6));
  w.put(static_cast<std::uint64_t>(m.merge_seconds * 1e6));
  w.put(static_cast<std::uint64_t>(m.absorb_seconds * 1e6));
  return std::move(w.bytes());
}

BatchMerges decode_merges(std::span<const std::byte> bytes) {
  BatchMerges m;
  if (bytes.empty()) return m;
  if (bytes.size() != 6 * sizeof(std::uint64_t))
    throw ProtocolError("DONE of an EXTRACT: " + std::to_string(bytes.size()) +
                        " bytes of batch merges, not the six u64 fields");
  ByteReader r(bytes);
  m.merges = r.get<std::uint64_t>();
  m.leaves = r.get<std::uint64_t>();
  m.bytes = r.get<std::uint64_t>();
  m.wire_seconds = static_cast<double>(r.get<std::uint64_t>()) / 1e6;
  m.merge_seconds = static_cast<double>(r.get<std::uint64_t>()) / 1e6;
  m.absorb_seconds = static_cast<double>(r.get<std::uint64_t>()) / 1e6;
  return m;
}

namespace {

using tandem::WorkingSurface;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Records from this size on give the freed memory back, as tandem's block driver does.
constexpr std::size_t kTrimRecordBytes = std::size_t{16} << 20;

class BatchDriver {
public:
  BatchDriver(const volume::Volume& volume, const tandem::BlockTree& tree, const std::vector<char>& skip,
              const tandem::TandemOptions& options, mesh::ComponentSink* sink, bool brute, BatchMerges& merges)
      : volume_(volume), tree_(tree), options_(options), sink_(sink), brute_(brute), merges_(merges),
        skipped_(tree.size(), 0), leaves_(tree.size(), 1) {
    // Per node: its leaves and those skipped, from the leaves up (ids put a parent before its children).
    std::size_t k = 0;
    for (NodeId leaf : tree.leaves())
      skipped_[static_cast<std::size_t>(leaf)] = skip[k++] != 0 ? 1 : 0;
    for (std::size_t i = tree.size(); i-- > 0;) {
      const tandem::BlockNode& n = tree.node(static_cast<NodeId>(i));
      if (n.is_leaf()) continue;
      const auto low = static_cast<std::size_t>(n.children[0]), high = static_cast<std::size_t>(n.children[1]);
      skipped_[i] = skipped_[low] + skipped_[high];
      leaves_[i] = leaves_[low] + leaves_[high];
    }
  }

  // As tandem's block driver (blocks_driver.cpp): the two sides of a node, the smaller travelling
  // to the other through its wire form; a side whose leaves are all skipped is no surface. The
  // count of leaves a surface holds goes with it (the merges' figures).
  std::unique_ptr<WorkingSurface> run(NodeId id, std::uint64_t& held) {
    const auto i = static_cast<std::size_t>(id);
    held = leaves_[i] - skipped_[i];
    if (held == 0) return nullptr;
    const tandem::BlockNode& node = tree_.node(id);
    if (node.is_leaf()) {
      std::unique_ptr<WorkingSurface> surface;
      tandem::extract_block(volume_, node.cells, options_, sink_, &surface, brute_);
      return surface;
    }
    std::uint64_t low_leaves = 0, high_leaves = 0;
    std::unique_ptr<WorkingSurface> low = run(node.children[0], low_leaves);
    if (low) low->compact(); // set aside while its brother is extracted
    std::unique_ptr<WorkingSurface> high = run(node.children[1], high_leaves);
    if (!low || !high) return low ? std::move(low) : std::move(high);
    const bool low_travels = low->triangle_count() < high->triangle_count();
    std::unique_ptr<WorkingSurface>& sent = low_travels ? low : high;
    std::unique_ptr<WorkingSurface>& kept = low_travels ? high : low;
    if (options_.cancel) options_.cancel->throw_if_cancelled();
    const auto t = Clock::now();
    std::vector<std::byte> record = tandem::serialize(std::move(*sent));
    sent.reset();
    const std::size_t bytes = record.size();
    if (bytes >= kTrimRecordBytes) tandem::release_slab_storage();
    const auto m = Clock::now();
    merges_.wire_seconds += std::chrono::duration<double>(m - t).count();
    tandem::merge_record(*kept, std::move(record), options_.cancel);
    merges_.merge_seconds += seconds_since(m);
#if defined(__GLIBC__)
    if (bytes >= kTrimRecordBytes) malloc_trim(0);
#endif
    ++merges_.merges;
    merges_.leaves += low_travels ? low_leaves : high_leaves;
    merges_.bytes += bytes;
    return std::move(kept);
  }

private:
  const volume::Volume& volume_;
  const tandem::BlockTree& tree_;
  const tandem::TandemOptions& options_;
  mesh::ComponentSink* sink_;
  bool brute_;
  BatchMerges& merges_;
  std::vector<std::uint32_t> skipped_, leaves_;
};

} // namespace

std::unique_ptr<tandem::WorkingSurface> extract_batch(const volume::Volume& volume, const volume::Box& cells,
                                                      std::int64_t leaf, const LeafRuns& skip,
                                                      const tandem::TandemOptions& options, mesh::ComponentSink* sink,
                                                      bool brute, BatchMerges* merges) {
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
  BatchMerges ignored;
  BatchDriver driver(volume, tree, skipped, options, sink, brute, merges ? *merges : ignored);
  std::uint64_t held = 0;
  return driver.run(tree.root(), held);
}

} // namespace geotandem::runtime::detail
