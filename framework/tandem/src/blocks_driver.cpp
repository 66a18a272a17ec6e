// The block tree driven in one process (blocks.hpp): leaves by extract_block, brothers merged
// bottom-up, the smaller of two brothers shipped through its wire form and taken in from it.
#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <string>

#include "geotandem/core/error.hpp"
#include "geotandem/tandem/block_tree.hpp"
#include "geotandem/tandem/blocks.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "geotandem/tandem/serialize.hpp"

namespace geotandem::tandem {
namespace {

using Clock = std::chrono::steady_clock;

// Merges whose record reaches this size give the freed memory back to the system.
constexpr std::size_t kTrimRecordBytes = std::size_t{16} << 20;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Forwards the units of each leaf's task to the one task of the whole extraction (extract_block
// begins and ends a task per block; the user sees one).
class ForwardingProgress final : public Progress {
public:
  explicit ForwardingProgress(Progress* to) : to_(to) {}
  void begin(const std::string&, std::uint64_t, const std::string&) override { done_ = 0; }
  void update(std::uint64_t done) override {
    if (done <= done_) return;
    if (to_) to_->advance(done - done_);
    done_ = done;
  }
  void end() override {}

private:
  Progress* to_;
};

class Driver {
public:
  Driver(const volume::Volume& volume, const BlockTree& tree, const TandemOptions& options, mesh::ComponentSink* sink,
         bool brute)
      : volume_(volume), tree_(tree), options_(options), sink_(sink), brute_(brute), forward_(options.progress) {
    leaf_options_ = options;
    leaf_options_.progress = options.progress ? &forward_ : nullptr;
  }

  std::unique_ptr<WorkingSurface> run(NodeId id) {
    const BlockNode& node = tree_.node(id);
    if (node.is_leaf()) return leaf(node);
    std::unique_ptr<WorkingSurface> low = run(node.children[0]);
    low->compact(); // set aside while its brother is extracted
    held_ += low->triangle_count();
    std::unique_ptr<WorkingSurface> high = run(node.children[1]);
    held_ -= low->triangle_count();
    // The runtime sends the smaller brother, as a record, to the worker holding the other, which
    // takes it in from the record; the sender's copy goes first, as on another machine.
    const bool low_travels = low->triangle_count() < high->triangle_count();
    std::unique_ptr<WorkingSurface>& sent = low_travels ? low : high;
    std::unique_ptr<WorkingSurface>& kept = low_travels ? high : low;
    const SimplifyCounters before = kept->counters(), other = sent->counters();
    if (options_.cancel) options_.cancel->throw_if_cancelled();
    std::size_t record_bytes = 0;
    {
      const auto t = Clock::now();
      std::vector<std::byte> record = serialize(std::move(*sent));
      sent.reset();
      stats_.seconds_wire += seconds_since(t);
      record_bytes = record.size();
      // The large merges make the peak: the slab kept for the next leaf goes back first (the next
      // leaf allocates one again).
      if (record_bytes >= kTrimRecordBytes) release_slab_storage();
      stats_.wire_bytes += record.size();
      stats_.largest_record = std::max<std::uint64_t>(stats_.largest_record, record.size());
      const auto m = Clock::now();
      stats_.components_at_merges += merge_record(*kept, std::move(record), options_.cancel);
      stats_.seconds_merge += seconds_since(m);
    }
#if defined(__GLIBC__)
    // A merge frees the sender's surface, its record and their copies: large blocks, many in the
    // heap below glibc's self-raising mmap threshold, whose free pages glibc keeps. Give them back
    // after the large merges (malloc_trim releases free pages inside the heap too). After every
    // merge it cost twice the system time at 1024^3 (pages given back and faulted in again).
    if (record_bytes >= kTrimRecordBytes) malloc_trim(0);
#endif
    stats_.seam_collapses += kept->counters().collapses - before.collapses - other.collapses;
    ++stats_.merges;
    note(kept->triangle_count());
    if (options_.progress) options_.progress->advance();
    return std::move(kept);
  }

  BlocksStats& stats() {
    return stats_;
  }

private:
  std::unique_ptr<WorkingSurface> leaf(const BlockNode& node) {
    const auto t = Clock::now();
    std::unique_ptr<WorkingSurface> surface;
    const TandemStats s = extract_block(volume_, node.cells, leaf_options_, sink_, &surface, brute_);
    stats_.seconds_leaves += seconds_since(t);
    ++stats_.leaves;
    TandemStats& total = stats_.tandem;
    total.layers.insert(total.layers.end(), s.layers.begin(), s.layers.end());
    for (const LayerStats& layer : s.layers)
      note(layer.triangles_in_memory);
    note(s.final_pass.triangles_in_memory);
    return surface;
  }

  void note(std::uint64_t triangles) {
    stats_.tandem.peak_triangles = std::max(stats_.tandem.peak_triangles, triangles);
    stats_.peak_held_triangles = std::max(stats_.peak_held_triangles, held_ + triangles);
  }

  const volume::Volume& volume_;
  const BlockTree& tree_;
  const TandemOptions& options_;
  TandemOptions leaf_options_;
  mesh::ComponentSink* sink_;
  bool brute_;
  ForwardingProgress forward_;
  std::uint64_t held_ = 0;
  BlocksStats stats_;
};

} // namespace

std::unique_ptr<WorkingSurface> extract_subtree(const volume::Volume& volume, const volume::Box& cells,
                                                std::int64_t block_size, const TandemOptions& options,
                                                mesh::ComponentSink* sink, bool brute) {
  const volume::Box cube = cube_cells(volume.geometry().shape);
  if (cells.empty() || !cube.contains(cells) || block_size <= 0)
    throw InvalidArgument("extract subtree: cells " + cells.to_string() + " are empty or leave the cube's cells " +
                              cube.to_string() + ", or the leaf size is not positive",
                          {.block = cells.to_string()});
  const BlockTree tree(cells, block_size);
  TandemOptions quiet = options;
  quiet.progress = nullptr;
  Driver driver(volume, tree, quiet, sink, brute);
  return driver.run(tree.root());
}

BlocksStats extract_blocks(const volume::Volume& volume, const volume::Box& cells, std::int64_t block_size,
                           const TandemOptions& options, mesh::ComponentSink* sink,
                           std::unique_ptr<WorkingSurface>* remaining, bool brute) {
  const auto start = Clock::now();
  options.simplify.validate();
  const volume::Box cube = cube_cells(volume.geometry().shape);
  if (cells.empty() || !cube.contains(cells))
    throw InvalidArgument("extract blocks: cells " + cells.to_string() + " are empty or leave the cube's cells " +
                              cube.to_string(),
                          {.block = cells.to_string()});
  const std::int64_t largest = std::max({cells.size(0), cells.size(1), cells.size(2)});
  const BlockTree tree(cells, block_size <= 0 ? largest : block_size);

  if (options.progress) {
    std::uint64_t units = 0;
    for (NodeId leaf : tree.leaves())
      units += static_cast<std::uint64_t>(tree.node(leaf).cells.size(options.axis));
    units += tree.leaves().size() - 1; // one per merge
    options.progress->begin("tandem, " + std::to_string(tree.leaves().size()) + " block" +
                                (tree.leaves().size() == 1 ? "" : "s"),
                            units, "layers+merges");
  }
  Driver driver(volume, tree, options, sink, brute);
  std::unique_ptr<WorkingSurface> root = driver.run(tree.root());

  BlocksStats& stats = driver.stats();
  TandemStats& total = stats.tandem;
  const auto t = Clock::now();
  const SimplifyCounters before = root->counters();
  LayerStats& f = total.final_pass;
  f.rank = total.layers.empty() ? 0 : total.layers.back().rank + 1;
  root->finish(options.cancel);
  const SimplifyCounters& after = root->counters();
  f.count(before, after);
  f.triangles_in_memory = root->triangle_count();
  f.vertices_in_memory = root->vertex_count();
  f.seconds_simplify = seconds_since(t);
  stats.seconds_merge += f.seconds_simplify;
  stats.components_at_merges += f.components_dumped;
  total.counters = after;
  total.remaining_triangles = root->triangle_count();
  total.seconds_total = seconds_since(start);
  // The slab this thread kept for a next leaf is not needed after the last one.
  release_slab_storage();
  if (options.progress) options.progress->end();
  if (remaining) *remaining = std::move(root);
  return stats;
}

} // namespace geotandem::tandem
