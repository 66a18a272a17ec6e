// A batch that spans finished leaves (issue 55): the worker's side (extract_batch skips them) and the
// manager's (the runs of leaf ordinals it names), on a real analytic cube against the in-process
// extraction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "../../framework/runtime/src/batch_extract.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/runtime/aggregate.hpp"
#include "geotandem/runtime/protocol.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "geotandem/tandem/blocks.hpp"
#include "geotandem/tandem/extraction_options.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "geotandem/tandem/region.hpp"
#include "schedule_support.hpp"

namespace geotandem::runtime {
namespace {

using tandem::BlockTree;
using tandem::NodeId;

// Key -> volume of every component committed.
class Volumes final : public mesh::ComponentSink {
public:
  void commit(const mesh::Component& c) override {
    EXPECT_FALSE(by_key.count(c.key)) << "component " << c.key << " committed twice";
    by_key[c.key] = c.stats.volume;
  }
  std::map<std::uint64_t, double> by_key;
};

struct Cube {
  std::unique_ptr<synth::SyntheticCube> volume;
  tandem::TandemOptions options;
  volume::Box cells;
  Cube() {
    synth::AnalyticOptions o;
    o.shape = {49, 45, 41};
    o.seed = 3;
    volume = synth::make_analytic(o);
    tandem::ExtractionOptions e;
    e.iso = static_cast<float>(synth::analytic_iso);
    options = tandem::loop_options(e);
    cells = tandem::cube_cells(volume->geometry().shape);
  }
};

// A killed run finished the leaves of the batches (subtrees of at most 8 leaves) whose surface was
// empty once extracted: every component of theirs was committed then. A resumed batch over the whole
// cube that skips them gives, with what they committed, the in-process run's components: each once,
// the same volumes.
TEST(BatchExtract, SkippedFinishedLeavesGiveTheComponentsOfTheInProcessRun) {
  const Cube c;
  Volumes reference;
  tandem::extract_blocks(*c.volume, c.cells, 8, c.options, &reference);
  ASSERT_GT(reference.by_key.size(), 5u);

  const BlockTree tree(c.cells, 8);
  Volumes before; // what the finished leaves committed in the killed run
  std::vector<char> finished(tree.leaves().size(), 0);
  std::vector<std::uint32_t> ordinal(tree.size(), 0);
  for (std::size_t i = 0; i < tree.leaves().size(); ++i)
    ordinal[static_cast<std::size_t>(tree.leaves()[i])] = static_cast<std::uint32_t>(i);
  std::size_t batches = 0, empty = 0;
  for (NodeId n = 0; n < static_cast<NodeId>(tree.size()); ++n) {
    const tandem::BlockNode& node = tree.node(n);
    const NodeId end = subtree_end(tree, n);
    const auto leaves = static_cast<std::size_t>(std::count_if(tree.leaves().begin(), tree.leaves().end(),
                                                               [&](NodeId leaf) { return leaf >= n && leaf < end; }));
    const bool batch = leaves <= 8 && (n == tree.root() || subtree_end(tree, node.parent) - node.parent > 2 * 8);
    if (!batch) continue;
    ++batches;
    Volumes mine;
    std::unique_ptr<tandem::WorkingSurface> rest =
        node.is_leaf() ? nullptr : tandem::extract_subtree(*c.volume, node.cells, 8, c.options, &mine);
    if (node.is_leaf()) tandem::extract_block(*c.volume, node.cells, c.options, &mine, &rest);
    // Every other empty one: the batch must still extract the empty ones it is not told to skip.
    if (rest && rest->component_count() > 0) continue;
    if (empty++ % 2 == 1) continue;
    for (NodeId leaf = n; leaf < end; ++leaf)
      if (tree.node(leaf).is_leaf()) finished[ordinal[static_cast<std::size_t>(leaf)]] = 1;
    for (const auto& [key, v] : mine.by_key)
      before.by_key[key] = v;
  }
  ASSERT_GT(batches, 4u);
  detail::LeafRuns runs;
  for (std::uint32_t i = 0; i < finished.size(); ++i)
    if (finished[i]) {
      if (!runs.empty() && runs.back().first + runs.back().second == i)
        ++runs.back().second;
      else
        runs.emplace_back(i, 1);
    }
  ASSERT_FALSE(runs.empty());
  ASSERT_GT(before.by_key.size(), 0u) << "no finished leaf held a component of its own: a weak test";
  // Through the wire form, as the manager sends them.
  const detail::LeafRuns sent = detail::decode_runs(detail::encode_runs(runs));
  ASSERT_EQ(sent, runs);

  Volumes after;
  detail::BatchMerges merges;
  std::unique_ptr<tandem::WorkingSurface> surface =
      detail::extract_batch(*c.volume, c.cells, 8, sent, c.options, &after, false, &merges);
  ASSERT_TRUE(surface);
  // Its merges are reported for the task log (one fewer than the surfaces merged, each with a
  // record that travelled), through the DONE's wire form.
  std::size_t extracted = 0;
  for (char f : finished)
    extracted += f ? 0 : 1;
  EXPECT_GT(merges.merges, 0u);
  EXPECT_LT(merges.merges, extracted);
  EXPECT_GE(merges.leaves, merges.merges);
  EXPECT_GT(merges.bytes, 0u);
  const detail::BatchMerges back = detail::decode_merges(detail::encode_merges(merges));
  EXPECT_EQ(back.merges, merges.merges);
  EXPECT_EQ(back.bytes, merges.bytes);
  EXPECT_NEAR(back.merge_seconds, merges.merge_seconds, 1e-6);
  surface->set_region(tandem::Region::block(c.cells, c.cells)); // the final pass, as worker.cpp's
  surface->finish();
  for (const auto& [key, v] : before.by_key) {
    EXPECT_FALSE(after.by_key.count(key)) << "component " << key << " of a finished leaf committed again";
    after.by_key[key] = v;
  }
  ASSERT_EQ(after.by_key.size(), reference.by_key.size());
  for (const auto& [key, v] : reference.by_key) {
    ASSERT_TRUE(after.by_key.count(key)) << "component " << key << " lost";
    EXPECT_NEAR(after.by_key.at(key), v, 0.005 * std::abs(v) + 1e-9) << "component " << key;
  }
}

// Runs that leave the batch's leaves (the manager split another tree) or bytes that are not whole
// pairs are refused before anything is extracted.
TEST(BatchExtract, RunsOutsideTheBatchAreRefused) {
  const Cube c;
  Volumes sink;
  EXPECT_THROW(detail::extract_batch(*c.volume, c.cells, 8, {{0, 1}, {600, 10}}, c.options, &sink, false),
               InvalidArgument);
  EXPECT_TRUE(sink.by_key.empty());
  EXPECT_THROW(detail::decode_runs(std::vector<std::byte>(12)), ProtocolError);
  EXPECT_THROW(detail::decode_merges(std::vector<std::byte>(12)), ProtocolError);
}

// The manager's side: the runs name exactly the finished leaves of the batch's subtree, by their
// ordinal among its leaves, and as many as the decision counts.
TEST(BatchExtract, TheManagerNamesTheFinishedLeavesOfTheBatch) {
  const BlockTree tree(schedule_test::cells(64, 64, 32), 8);
  Schedule s(tree);
  std::set<NodeId> skipped;
  for (std::size_t i = 0; i < tree.leaves().size(); ++i)
    if (i % 5 == 1 || i % 7 == 3) {
      s.skip(tree.leaves()[i]);
      skipped.insert(tree.leaves()[i]);
    }
  s.join(1);
  s.set_batch(16);
  const Decision d = s.next(1);
  ASSERT_EQ(d.kind, TaskKind::extract);
  ASSERT_EQ(s.leaves_under(d.leaf), 16u);
  const detail::LeafRuns runs = detail::finished_runs(tree, s, d.leaf);
  std::vector<NodeId> leaves; // of the batch, in tree order
  for (NodeId leaf : tree.leaves())
    if (tree.is_ancestor(d.leaf, leaf)) leaves.push_back(leaf);
  std::set<NodeId> named;
  for (const auto& [first, count] : runs)
    for (std::uint32_t i = first; i < first + count; ++i)
      named.insert(leaves.at(i));
  std::set<NodeId> expected;
  for (NodeId leaf : leaves)
    if (skipped.count(leaf)) expected.insert(leaf);
  EXPECT_EQ(named, expected);
  EXPECT_EQ(named.size(), d.finished);
  EXPECT_GT(d.finished, 0u);
}

} // namespace
} // namespace geotandem::runtime
