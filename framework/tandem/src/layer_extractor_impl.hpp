#pragma once
// The state of LayerExtractor (marching_cubes.hpp), shared by the layer's edges and triangles
// (marching_cubes.cpp) and the caps that close bodies cut by the cube's border (mc_cap_layers.cpp).
// Internal to the tandem part.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "geotandem/tandem/marching_cubes.hpp"
#include "mc_table.hpp"
#include "slab_reader.hpp"

namespace geotandem::tandem {

// The families of lattice edges of a layer: in cross-section A (rank - 1) along u or v, in
// cross-section B (rank) along u or v, and across (along the axis, from A to B).
enum EdgeArray : std::uint8_t { a_u = 0, a_v, b_u, b_v, across, edge_array_count };

struct LayerExtractor::Impl {
  struct EdgeSlot {
    EdgeArray array;
    std::uint8_t du, dv;
  };

  const volume::Volume& volume;
  volume::Box box; // the cells
  McOptions options;
  LatticeIds lattice;
  int a = 0, u = 1, v = 2;                     // extraction axis, then the slower and faster in-plane axes
  std::int64_t nu = 0, nv = 0, su = 0, sv = 0; // cells and samples of a cross-section along u and v
  std::int64_t words = 0;                      // 64-bit words per row of sign bits
  std::int64_t rank = 0;                       // the next layer's rank
  bool first_read = false;
  std::unique_ptr<detail::SlabReader> slabs; // the block's samples, a slab of sections at a time
  std::vector<float> values[2];              // [0]: cross-section rank - 1 ("A"), [1]: cross-section rank ("B")
  std::vector<std::uint64_t> signs[2];       // sign bits of the same
  // Vertex number per crossed edge, row stride sv, relative to the first vertex of its
  // cross-section (or of the edges across): [buffer][0 = along u, 1 = along v], and across.
  std::vector<std::uint32_t> plane_slots[2][2];
  std::vector<std::uint32_t> across_slots;
  // Vertex number per inside sample on the cube's border (caps), relative like plane_slots.
  std::vector<std::uint32_t> sample_slots[2];
  // The vertices of cross-section B of the last layer, which are cross-section A's of the next.
  std::vector<std::uint64_t> kept_ids;
  std::vector<std::array<double, 3>> kept_positions;
  std::vector<std::int64_t> kept_samples;
  bool have_kept = false;
  EdgeSlot edge_slot[detail::kCellEdges]{};
  std::uint8_t local_to_case[256]{};

  Impl(const volume::Volume& vol, const volume::Box& cells, const McOptions& opts);
  void read(int which, std::int64_t section);
  void emit_plane(int which, Layer& out);
  void emit_samples(int which, Layer& out, std::uint32_t first);
  void emit_across(Layer& out);
  void emit_caps(Layer& out, std::uint32_t b_first, std::uint32_t across_first) const;
  bool inside(int which, std::int64_t iu, std::int64_t iv) const {
    return ((signs[which][static_cast<std::size_t>(iu * words + (iv >> 6))] >> (iv & 63)) & 1u) != 0;
  }
  void emit_triangles(Layer& out, const std::uint32_t (&base)[edge_array_count]) const;
  volume::Index3 at(std::int64_t section, std::int64_t iu, std::int64_t iv) const {
    volume::Index3 g{};
    g[a] = section;
    g[u] = box.lo[u] + iu;
    g[v] = box.lo[v] + iv;
    return g;
  }
  std::uint32_t add_vertex(Layer& out, volume::Index3 p0, int axis, float v0, float v1) const;
};

} // namespace geotandem::tandem
