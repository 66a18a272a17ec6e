// Merging records whose content is forged but whose checksums are valid (issue 52): real records of
// real extractions (several block layouts of an analytic cube), mutated in many ways (random byte
// flips, targeted edits of counts, indices, lattice ids, components, edges, blocks), resealed with
// a correct length and XXH64. merge_record must either refuse the record with a DataError or leave a
// surface the engine's invariants hold for (a 2-manifold, consistently oriented, whose finished
// components are closed); never crash (run under the asan preset in CI).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "blocks_support.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/mesh/topology.hpp"
#include "geotandem/tandem/block_tree.hpp"
#include "geotandem/tandem/serialize.hpp"
#include "geotandem/tandem/tandem.hpp"
#include "surface_record_layout.hpp"

namespace geotandem::tandem {
namespace {

using Bytes = testing::RecordBytes;
using Layout = testing::RecordLayout;
using fixtures::CollectingSink;
using testing::reseal;

template <class T> T get(const Bytes& r, std::size_t at) {
  return testing::record_get<T>(r, at);
}
template <class T> void put(Bytes& r, std::size_t at, T v) {
  testing::record_put(r, at, v);
}

// One mutation of `r` (kind `kind`, parameters from `rng`), with a description for messages.
std::string mutate(Bytes& r, int kind, std::mt19937_64& rng) {
  const Layout l(r);
  auto pick = [&rng](std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(rng() % n); };
  auto vertex = [&](std::size_t i) { return l.vertex(i); };
  auto corner = [&](std::size_t t, std::size_t c) { return l.corner(t, c); };
  const std::size_t v = pick(l.nv), t = pick(l.nt), e = pick(l.ne);
  if (l.nv == 0 || l.nt == 0) kind = 0; // nothing to aim at (the cases hold triangles)
  switch (kind) {
  case 0: { // random bytes of the payload
    const std::size_t flips = 1 + pick(4);
    for (std::size_t k = 0; k < flips; ++k)
      r[kSurfaceWireHeaderSize + pick(r.size() - kSurfaceWireHeaderSize)] ^=
          std::byte{static_cast<std::uint8_t>(1u << pick(8))};
    return "payload bytes flipped";
  }
  case 1: put(r, corner(t, pick(3)), static_cast<std::uint32_t>(l.nv + pick(3))); return "triangle corner out of range";
  case 2: put(r, corner(t, 1), get<std::uint32_t>(r, corner(t, 0))); return "triangle corner repeated";
  case 3: { // orientation flipped
    const auto a = get<std::uint32_t>(r, corner(t, 1)), b = get<std::uint32_t>(r, corner(t, 2));
    put(r, corner(t, 1), b);
    put(r, corner(t, 2), a);
    return "triangle flipped";
  }
  case 4: put(r, corner(t, pick(3)), static_cast<std::uint32_t>(pick(l.nv))); return "triangle corner moved";
  case 5: { // a triangle copied over another
    const std::size_t u = (t + 1 + pick(l.nt - 1)) % l.nt;
    std::memcpy(r.data() + corner(u, 0), r.data() + corner(t, 0), Layout::kTriangle);
    return "triangle duplicated";
  }
  case 6: put(r, vertex(v) + 128, get<std::uint64_t>(r, vertex(pick(l.nv)) + 128)); return "lattice id copied";
  case 7: put(r, vertex(v) + 128, get<std::uint64_t>(r, vertex(v) + 128) + 1 + pick(6)); return "lattice id shifted";
  case 8: put(r, vertex(v) + 128, std::numeric_limits<std::uint64_t>::max()); return "lattice id removed";
  case 9: put(r, vertex(v) + 136, static_cast<std::int32_t>(pick(l.nc + 4)) - 2); return "component changed";
  case 10: { // position moved, made huge or not a number
    const double values[] = {std::nan(""), 1e300, get<double>(r, vertex(v) + 8 * pick(3)) + 0.25, -7.0};
    put(r, vertex(v) + 8 * pick(3), values[pick(4)]);
    return "position changed";
  }
  case 11: put(r, vertex(v) + 112, pick(2) ? -1.0 : 0.0); return "radius not positive";
  case 12: // queued edge's ends or state
    if (l.ne == 0) return "no edge";
    if (pick(2))
      put(r, l.edges + Layout::kEdge * e + 4 * pick(2), static_cast<std::uint32_t>(pick(l.nv + 2)));
    else
      put(r, l.edges + Layout::kEdge * e + 8, static_cast<std::uint8_t>(pick(4)));
    return "queued edge changed";
  case 13: // a component's key
    if (l.nc == 0) return "no component";
    put(r, l.components + 8 * pick(l.nc), pick(2) ? get<std::uint64_t>(r, l.components) : rng());
    return "component key changed";
  case 14: { // a block moved or resized by a cell
    const std::size_t at = l.blocks + 48 * pick(l.nb) + 8 * pick(6);
    put(r, at, get<std::int64_t>(r, at) + (pick(2) ? 1 : -1));
    return "block changed";
  }
  case 15: { // a count one off (the sections after it shift)
    const std::size_t counts[] = {l.components_count, l.vertices_count, l.triangles_count, l.edges_count};
    const std::size_t at = counts[pick(4)];
    put(r, at, get<std::uint64_t>(r, at) + (pick(2) ? 1 : std::uint64_t(-1)));
    return "count changed";
  }
  case 16: put(r, l.axis, get<std::int32_t>(r, l.axis) + 1 + static_cast<std::int32_t>(pick(3))); return "axis changed";
  case 17: put(r, l.front, pick(2) ? 3.0 : -std::numeric_limits<double>::infinity()); return "front changed";
  default: { // a random 32-bit word of the triangles or vertices
    const std::size_t at = pick(2) ? corner(t, 0) : vertex(v) + 4 * pick(Layout::kVertex / 4);
    put(r, at, static_cast<std::uint32_t>(rng()));
    return "word overwritten";
  }
  }
}
constexpr int kKinds = 19;

// A receiver and the record merged into it, both real: a fold of one layout's leaves in tree
// order, taken at one step, in either direction (the smaller side into the larger, or the larger
// into the smaller, whose record then holds many blocks).
struct Case {
  std::string name;
  Bytes receiver, record;
};

std::vector<Case> cases() {
  static const auto volume = blocks_test::sample(blocks_test::bodies(), blocks_test::kShape);
  std::vector<Case> out;
  for (std::int64_t leaf : {32, 24, 16}) {
    const BlockTree tree(cube_cells(blocks_test::kShape), leaf);
    TandemOptions options;
    options.simplify.max_error = blocks_test::kMaxError;
    std::unique_ptr<WorkingSurface> all;
    const std::vector<NodeId> leaves = tree.leaves();
    std::size_t taken = 0, next = 1;
    for (std::size_t k = 0; k < leaves.size(); ++k) {
      std::unique_ptr<WorkingSurface> piece;
      extract_block(*volume, tree.node(leaves[k]).cells, options, nullptr, &piece);
      if (!all) {
        all = std::move(piece);
        continue;
      }
      // Three steps spread over the fold and the last one, where both sides hold triangles.
      const bool held = piece->triangle_count() > 0 && all->triangle_count() > 0;
      if (held && ((taken < 3 && k >= next) || k + 1 == leaves.size())) {
        ++taken;
        next = k + leaves.size() / 4;
        const std::string name = "leaf " + std::to_string(leaf) + ", step " + std::to_string(k);
        out.push_back({name + ", leaf into the fold", serialize(*all), serialize(*piece)});
        out.push_back({name + ", fold into the leaf", serialize(*piece), serialize(*all)});
      }
      merge_record(*all, serialize(*piece));
    }
  }
  return out;
}

// The surface after a merge that went through: indices in range (check_topology throws otherwise),
// a 2-manifold with one orientation, and closed components once it is finished.
void expect_invariants(WorkingSurface& into, CollectingSink& sink, const std::string& what) {
  const mesh::TopologyReport t = mesh::check_topology(into.snapshot());
  EXPECT_TRUE(t.is_manifold() && t.misoriented_edges == 0) << what << ": " << t.summary();
  sink.components.clear();
  into.finish();
  for (const mesh::Component& c : sink.components) {
    const mesh::TopologyReport ct = mesh::check_topology(c.surface);
    EXPECT_TRUE(ct.is_closed_manifold()) << what << ": component " << c.key << ": " << ct.summary();
  }
}

TEST(TandemRecordMutation, AForgedRecordIsRefusedOrMergesIntoAValidSurface) {
  const std::vector<Case> all = cases();
  ASSERT_GE(all.size(), 18u);
  std::mt19937_64 rng(52);
  std::size_t refused = 0, merged = 0;
  std::vector<std::size_t> refused_by_kind(kKinds, 0);
  for (const Case& c : all) {
    SCOPED_TRACE(c.name);
    { // the real record goes in, and the surface holds
      CollectingSink sink;
      WorkingSurface into = deserialize(c.receiver, &sink);
      ASSERT_NO_THROW(merge_record(into, c.record));
      expect_invariants(into, sink, "unchanged record");
    }
    for (int trial = 0; trial < 3 * kKinds; ++trial) {
      const int kind = trial % kKinds;
      Bytes mutant = c.record;
      const std::string what = mutate(mutant, kind, rng) + " (trial " + std::to_string(trial) + ")";
      reseal(mutant);
      CollectingSink sink;
      WorkingSurface into = deserialize(c.receiver, &sink);
      try {
        merge_record(into, mutant);
      } catch (const DataError& e) {
        ++refused;
        ++refused_by_kind[static_cast<std::size_t>(kind)];
        const std::string text = e.what(); // names the record, or the two regions of the merge
        EXPECT_TRUE(text.find("record") != std::string::npos || text.find("merging {") != std::string::npos)
            << what << ": " << text;
        continue;
      }
      ++merged;
      expect_invariants(into, sink, what);
    }
  }
  // The targeted edits that always break an invariant are all refused.
  for (int kind : {1, 2, 3, 5, 11, 16})
    EXPECT_EQ(refused_by_kind[static_cast<std::size_t>(kind)], 3 * all.size()) << "mutation kind " << kind;
  std::cout << "forged records: " << refused << " refused, " << merged << " merged into a valid surface\n";
}

} // namespace
} // namespace geotandem::tandem
