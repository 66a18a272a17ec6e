// Marching cubes by blocks and by layers: blocks weld into exactly the one-block surface, layers
// keep their contract, at most two cross-sections are read at a time, and bad input is refused.

#include <gtest/gtest.h>

#include <set>
#include <thread>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/topology.hpp"
#include "geotandem/tandem/block_tree.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "mc_support.hpp"

namespace geotandem::tandem {
namespace {

using namespace testing;

// Two overlapping blobs, a thin sheet and noise: smooth parts, ambiguous parts, and a surface
// that reaches the cube's border (the sheet), so open surfaces are compared too.
std::unique_ptr<volume::MemoryVolume> mixed_field(const Index3& shape, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> jitter(-0.35f, 0.35f);
  return field(shape, [&](double i, double j, double k) {
    const float blobs = std::max(sphere({5.3, 6.1, 7.2}, 4.4)(i, j, k), sphere({12.2, 8.7, 9.9}, 3.7)(i, j, k));
    const float sheet = static_cast<float>(0.8 - std::abs(k - 0.4 * i - 2.3));
    return std::max(blobs, sheet) + jitter(rng);
  });
}

IdSurface by_blocks(const volume::Volume& v, const std::vector<Box>& blocks, float iso, int axis) {
  IdSurface s;
  for (const Box& b : blocks) {
    std::vector<std::uint64_t> ids;
    const mesh::SurfaceMesh part = extract_surface(v, b, McOptions{iso, axis}, &ids);
    add_to(s, part, ids);
  }
  return s;
}

// The cube's cells cut into n0 x n1 x n2 boxes of uneven sizes (growing along each axis).
std::vector<Box> grid(const Box& cells, const Index3& n) {
  std::vector<Box> out;
  auto cut = [&](int a, std::int64_t m) { return cells.lo[a] + (cells.size(a) * m * (m + 1)) / (n[a] * (n[a] + 1)); };
  for (std::int64_t x = 0; x < n[0]; ++x)
    for (std::int64_t y = 0; y < n[1]; ++y)
      for (std::int64_t z = 0; z < n[2]; ++z) {
        out.push_back(Box{{cut(0, x), cut(1, y), cut(2, z)}, {cut(0, x + 1), cut(1, y + 1), cut(2, z + 1)}});
        EXPECT_FALSE(out.back().empty()) << out.back().to_string();
      }
  return out;
}

TEST(McBlocks, BlocksWeldIntoExactlyTheOneBlockSurface) {
  const auto v = mixed_field({18, 15, 17}, 3);
  const Box all = cube_cells(v->geometry().shape);
  for (int axis = 0; axis < 3; ++axis) {
    const IdSurface whole = by_blocks(*v, {all}, 0.0f, axis);
    ASSERT_GT(whole.triangles.size(), 500u);
    std::vector<std::vector<Box>> splits = {grid(all, {2, 1, 1}), grid(all, {1, 1, 2}), grid(all, {2, 2, 2}),
                                            grid(all, {4, 4, 4})};
    std::vector<Box> leaves;
    const BlockTree tree(all, 5);
    for (NodeId leaf : tree.leaves())
      leaves.push_back(tree.node(leaf).cells);
    splits.push_back(leaves);
    EXPECT_EQ(splits[3].size(), 64u);
    for (const auto& blocks : splits) {
      const IdSurface parts = by_blocks(*v, blocks, 0.0f, axis);
      EXPECT_TRUE(parts.positions_agree) << blocks.size() << " blocks, axis " << axis;
      EXPECT_EQ(parts.triangles, whole.triangles) << blocks.size() << " blocks, axis " << axis;
      EXPECT_EQ(parts.positions, whole.positions) << blocks.size() << " blocks, axis " << axis; // bit-identical
    }
  }
}

TEST(McBlocks, WeldedBlocksOfAClosedFieldAreClosed) {
  const auto v = noise({14, 13, 15}, 11);
  const Box all = cube_cells(v->geometry().shape);
  const IdSurface parts = by_blocks(*v, grid(all, {4, 4, 4}), 0.0f, 1);
  const auto report = mesh::check_topology(to_mesh(parts));
  EXPECT_TRUE(report.is_closed_manifold()) << report.summary();
  EXPECT_EQ(report.degenerate_triangles, 0u);
}

TEST(McBlocks, LayersKeepTheirContract) {
  const auto v = mixed_field({16, 14, 15}, 5);
  const Box cells{{2, 1, 3}, {13, 12, 11}};
  for (int axis = 0; axis < 3; ++axis) {
    LayerExtractor x(*v, cells, McOptions{0.0f, axis});
    EXPECT_EQ(x.first_rank(), cells.lo[axis] + 1);
    EXPECT_EQ(x.last_rank(), cells.hi[axis]);
    const LatticeIds& ids = x.lattice();
    EXPECT_EQ(ids.shape, v->geometry().shape);
    Layer layer;
    std::int64_t expected = x.first_rank();
    std::size_t triangles = 0;
    while (x.next(layer)) {
      ASSERT_EQ(layer.rank, expected++);
      EXPECT_EQ(layer.axis, axis);
      ASSERT_EQ(layer.vertex_ids.size(), layer.positions.size());
      std::set<std::uint64_t> unique(layer.vertex_ids.begin(), layer.vertex_ids.end());
      EXPECT_EQ(unique.size(), layer.vertex_ids.size()) << "a vertex listed twice in layer " << layer.rank;
      std::vector<bool> used(layer.positions.size(), false);
      for (const auto& t : layer.triangles)
        for (std::uint32_t c : t) {
          ASSERT_LT(c, layer.positions.size());
          used[c] = true;
        }
      for (std::size_t i = 0; i < used.size(); ++i) {
        EXPECT_TRUE(used[i]) << "unused vertex in layer " << layer.rank;
        // Between the layer's two cross-sections, inside the block, on its lattice edge, and at
        // the position the documented formula gives from the lower-index end.
        const auto& p = layer.positions[i];
        EXPECT_GE(p[axis], static_cast<double>(layer.rank - 1));
        EXPECT_LE(p[axis], static_cast<double>(layer.rank));
        const Index3 s = ids.start(layer.vertex_ids[i]);
        const int e = ids.axis(layer.vertex_ids[i]);
        Index3 s1 = s;
        ++s1[e];
        for (int a = 0; a < 3; ++a) {
          EXPECT_GE(s[a], cells.lo[a]);
          EXPECT_LE(s1[a], cells.hi[a]);
        }
        const float v0 = v->samples()[v->geometry().bounds().offset(s)];
        const float v1 = v->samples()[v->geometry().bounds().offset(s1)];
        ASSERT_NE(v0 >= 0.0f, v1 >= 0.0f) << "vertex on an edge that is not crossed";
        double t = (0.0 - static_cast<double>(v0)) / (static_cast<double>(v1) - static_cast<double>(v0));
        t = std::clamp(t, kMcVertexMargin, 1.0 - kMcVertexMargin);
        for (int a = 0; a < 3; ++a)
          EXPECT_EQ(p[a], static_cast<double>(s[a]) + (a == e ? t : 0.0)) << "vertex " << layer.vertex_ids[i];
      }
      triangles += layer.triangles.size();
    }
    EXPECT_EQ(expected, x.last_rank() + 1);
    EXPECT_EQ(x.next_rank(), x.last_rank() + 1);
    EXPECT_FALSE(x.next(layer)); // stays finished
    EXPECT_TRUE(layer.triangles.empty());
    EXPECT_EQ(triangles, extract_surface(*v, cells, McOptions{0.0f, axis}).triangles.size());
  }
}

// McOptions::slab_samples sets how many cross-sections one read fetches; with one section's worth
// the extractor reads exactly one cross-section at a time.
TEST(McBlocks, ReadsOneCrossSectionAtATimeWithASmallSlab) {
  const auto v = mixed_field({12, 11, 13}, 7);
  const Box cells{{1, 2, 0}, {10, 9, 12}};
  for (int axis = 0; axis < 3; ++axis) {
    const RecordingVolume recording(*v);
    McOptions options{0.0f, axis};
    options.slab_samples = 1;
    LayerExtractor x(recording, cells, options);
    Layer layer;
    std::size_t layers = 0;
    while (x.next(layer)) {
      ++layers;
      // Before layer k is returned, exactly cross-sections lo .. k have been read.
      EXPECT_EQ(recording.reads().size(), layers + 1);
    }
    const auto& reads = recording.reads();
    ASSERT_EQ(reads.size(), static_cast<std::size_t>(cells.size(axis) + 1));
    for (std::size_t r = 0; r < reads.size(); ++r) {
      EXPECT_EQ(reads[r].size(axis), 1) << "read " << reads[r].to_string() << " is not one cross-section";
      EXPECT_EQ(reads[r].lo[axis], cells.lo[axis] + static_cast<std::int64_t>(r)) << "cross-sections out of order";
      for (int a = 0; a < 3; ++a)
        if (a != axis) {
          EXPECT_EQ(reads[r].lo[a], cells.lo[a]);
          EXPECT_EQ(reads[r].hi[a], cells.hi[a] + 1);
        }
    }
  }
}

// A computed volume's halo sets a floor on the slab: at least 8 halos of sections (with a budget of
// 3 sections, a halo of 1 gives 8), within 4 budgets (a halo of 3 would ask 24: 12 it is); the
// layers do not change.
TEST(McBlocks, SlabsHoldEightHalosOfSectionsWithinFourBudgets) {
  const auto v = mixed_field({30, 11, 13}, 7);
  const Box cells{{0, 2, 0}, {29, 9, 12}};
  const std::int64_t section = 8 * 13;
  std::vector<Layer> reference;
  for (const auto& [halo, expected] : {std::pair<std::int64_t, std::int64_t>{0, 3}, {1, 8}, {3, 12}}) {
    const RecordingVolume recording(*v, {halo, halo, halo});
    McOptions options{0.0f, 0};
    options.slab_samples = 3 * section;
    LayerExtractor x(recording, cells, options);
    std::vector<Layer> layers;
    for (Layer layer; x.next(layer);)
      layers.push_back(layer);
    const auto& reads = recording.reads();
    ASSERT_FALSE(reads.empty());
    EXPECT_EQ(reads.front().size(0), expected) << "halo " << halo;
    std::int64_t next = cells.lo[0];
    for (const Box& r : reads) {
      EXPECT_EQ(r.lo[0], next) << "halo " << halo << ": sections read twice or skipped";
      next = r.hi[0];
    }
    EXPECT_EQ(next, cells.hi[0] + 1);
    if (reference.empty()) {
      reference = layers;
      continue;
    }
    ASSERT_EQ(layers.size(), reference.size());
    for (std::size_t n = 0; n < layers.size(); ++n) {
      EXPECT_EQ(layers[n].vertex_ids, reference[n].vertex_ids) << "halo " << halo;
      EXPECT_EQ(layers[n].positions, reference[n].positions) << "halo " << halo;
      EXPECT_EQ(layers[n].triangles, reference[n].triangles) << "halo " << halo;
    }
  }
}

// With a larger budget the block's samples are read in slabs of consecutive cross-sections, each
// sample exactly once (a computed volume pays its halo once per slab), in order, never ahead of
// what the next layer needs by more than one slab; and the layers are the same whatever the slab.
TEST(McBlocks, ReadsEachSampleOnceInSlabsAndLayersDoNotDependOnTheSlab) {
  const auto v = mixed_field({12, 11, 13}, 7);
  const Box cells{{1, 2, 0}, {10, 9, 12}};
  for (int axis = 0; axis < 3; ++axis) {
    std::int64_t section = 1;
    for (int a = 0; a < 3; ++a)
      if (a != axis) section *= cells.size(a) + 1;
    const std::int64_t sections = cells.size(axis) + 1;
    std::vector<Layer> reference;
    for (const std::int64_t per_slab : {std::int64_t{1}, std::int64_t{3}, std::int64_t{4}, sections, sections + 5}) {
      const RecordingVolume recording(*v);
      McOptions options{0.0f, axis};
      options.slab_samples = per_slab * section;
      LayerExtractor x(recording, cells, options);
      std::vector<Layer> layers;
      for (Layer layer; x.next(layer);) {
        // Layer k needs cross-sections up to k; the reads reach at most one slab beyond.
        const Box& newest = recording.reads().back();
        EXPECT_GE(newest.hi[axis], layer.rank + 1);
        EXPECT_LE(newest.lo[axis], layer.rank) << "slab read before it was needed";
        layers.push_back(layer);
      }
      const auto& reads = recording.reads();
      const std::int64_t slab = std::min(per_slab, sections);
      ASSERT_EQ(static_cast<std::int64_t>(reads.size()), (sections + slab - 1) / slab) << "slab " << per_slab;
      std::int64_t next = cells.lo[axis];
      for (const Box& read : reads) {
        EXPECT_EQ(read.lo[axis], next) << "slabs must follow each other without overlap or gap";
        EXPECT_LE(read.size(axis), slab);
        next = read.hi[axis];
        for (int a = 0; a < 3; ++a)
          if (a != axis) {
            EXPECT_EQ(read.lo[a], cells.lo[a]);
            EXPECT_EQ(read.hi[a], cells.hi[a] + 1);
          }
      }
      EXPECT_EQ(next, cells.hi[axis] + 1);
      if (reference.empty()) {
        reference = layers;
        continue;
      }
      ASSERT_EQ(layers.size(), reference.size());
      for (std::size_t n = 0; n < layers.size(); ++n) {
        EXPECT_EQ(layers[n].rank, reference[n].rank);
        EXPECT_EQ(layers[n].vertex_ids, reference[n].vertex_ids) << "axis " << axis << ", slab " << per_slab;
        EXPECT_EQ(layers[n].positions, reference[n].positions) << "axis " << axis << ", slab " << per_slab;
        EXPECT_EQ(layers[n].triangles, reference[n].triangles) << "axis " << axis << ", slab " << per_slab;
      }
    }
  }
}

// An extractor takes over the slab storage of the one before it on the same thread (SlabReader):
// what it hands out comes from its own volume, never from what the last block left there. Each
// block's layers equal those its own thread extracts from scratch, whatever came before: a larger
// slab of another field, a smaller one, the same cells of another field, read whole (one slab, as
// the default budget reads a leaf) or four sections at a time.
TEST(McBlocks, AnExtractorAfterAnotherOnTheSameThreadReadsOnlyItsOwnVolume) {
  const auto first = mixed_field({14, 13, 15}, 11);
  const auto second = noise({14, 13, 15}, 12);
  const Box all = cube_cells(first->geometry().shape);
  const Box part{{2, 1, 3}, {9, 10, 8}};
  auto layers_of = [](const volume::Volume& v, const Box& cells, bool whole) {
    McOptions options{0.0f, 0};
    if (!whole) options.slab_samples = 4 * (cells.size(1) + 1) * (cells.size(2) + 1);
    LayerExtractor x(v, cells, options);
    std::vector<Layer> layers;
    for (Layer layer; x.next(layer);)
      layers.push_back(layer);
    return layers;
  };
  auto alone = [&](const volume::Volume& v, const Box& cells) {
    std::vector<Layer> layers;
    std::thread([&] { layers = layers_of(v, cells, false); }).join();
    return layers;
  };
  const std::vector<Layer> first_all = alone(*first, all), second_all = alone(*second, all);
  const std::vector<Layer> first_part = alone(*first, part), second_part = alone(*second, part);
  ASSERT_GT(second_part.size(), 3u);
  struct Step {
    const volume::Volume* volume;
    Box cells;
    const std::vector<Layer>* want;
  };
  const Step steps[] = {{first.get(), all, &first_all},   {second.get(), all, &second_all},
                        {first.get(), part, &first_part}, {second.get(), part, &second_part},
                        {first.get(), all, &first_all},   {second.get(), part, &second_part},
                        {first.get(), part, &first_part}};
  for (const bool whole : {true, false}) {
    std::size_t n = 0;
    for (const Step& step : steps) {
      const std::vector<Layer> got = layers_of(*step.volume, step.cells, whole);
      ASSERT_EQ(got.size(), step.want->size()) << "step " << n;
      for (std::size_t k = 0; k < got.size(); ++k) {
        const std::string where =
            "step " + std::to_string(n) + (whole ? " (whole)" : " (slabs)") + ", layer " + std::to_string(k);
        EXPECT_EQ(got[k].vertex_ids, (*step.want)[k].vertex_ids) << where;
        EXPECT_EQ(got[k].positions, (*step.want)[k].positions) << where;
        EXPECT_EQ(got[k].triangles, (*step.want)[k].triangles) << where;
      }
      ++n;
    }
  }
}

TEST(McBlocks, RefusesBadInput) {
  const auto v = noise({6, 7, 8}, 1);
  const Box all = cube_cells(v->geometry().shape);
  EXPECT_EQ(all, (Box{{0, 0, 0}, {5, 6, 7}}));
  auto make = [&v](const Box& cells, const McOptions& options) { LayerExtractor x(*v, cells, options); };
  EXPECT_THROW(make(all, McOptions{0.0f, 3}), InvalidArgument);
  EXPECT_THROW(make(all, McOptions{0.0f, -1}), InvalidArgument);
  EXPECT_THROW(make(all, McOptions{std::nanf(""), 0}), InvalidArgument);
  EXPECT_THROW(make(Box{{0, 0, 0}, {6, 6, 7}}, McOptions{}), InvalidArgument); // would read sample 6
  EXPECT_THROW(make(Box{{-1, 0, 0}, {5, 6, 7}}, McOptions{}), InvalidArgument);
  EXPECT_THROW(make(Box{{2, 0, 0}, {2, 6, 7}}, McOptions{}), InvalidArgument); // empty
  EXPECT_NO_THROW(make(all, McOptions{0.5f, 2}));
  try {
    make(Box{{0, 0, 0}, {6, 6, 7}}, McOptions{});
    ADD_FAILURE() << "a block reaching past the cube was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("[0:6"), std::string::npos) << e.what(); // names the block
  }
}

TEST(McBlocks, NanSamplesCountAsOutside) {
  auto v = field({8, 8, 8}, sphere({3.5, 3.5, 3.5}, 2.5));
  v->samples()[v->geometry().bounds().offset({3, 3, 3})] = std::nanf(""); // the centre
  v->samples()[v->geometry().bounds().offset({0, 0, 0})] = std::nanf(""); // far outside
  const mesh::SurfaceMesh s = extract_surface(*v, cube_cells({8, 8, 8}), McOptions{});
  const auto report = mesh::check_topology(s);
  EXPECT_TRUE(report.is_closed_manifold()) << report.summary();
  EXPECT_EQ(report.components, 2u); // the sphere and a small bubble around the NaN at its centre
  for (const auto& p : s.points)
    for (double c : p)
      EXPECT_TRUE(std::isfinite(c));
}

} // namespace
} // namespace geotandem::tandem
