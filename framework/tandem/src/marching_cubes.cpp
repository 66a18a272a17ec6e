// LayerExtractor: marching cubes one layer at a time, with two cross-sections in memory.
//
// Speed comes from sign bits: each cross-section is turned into rows of 64-bit words (bit set =
// inside), so 64 cells of a row are tested for "all corners on one side" with a handful of word
// operations, and crossed lattice edges are found with XORs. Every crossed edge of the layer gets
// its vertex once, before the cells are visited; cells then only look up vertex numbers. The
// vertices of cross-section k are kept from layer k for layer k + 1 instead of being computed again.

#include "geotandem/tandem/marching_cubes.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include "geotandem/core/error.hpp"
#include "layer_extractor_impl.hpp"

namespace geotandem::tandem {

namespace {

using volume::Box;
using volume::Index3;

// Bits [64 w, 64 w + 64) of a row that are below `limit`.
std::uint64_t mask_below(std::int64_t limit, std::int64_t w) {
  const std::int64_t n = limit - 64 * w;
  if (n >= 64) return ~std::uint64_t{0};
  if (n <= 0) return 0;
  return (std::uint64_t{1} << n) - 1;
}

// Bits iv and iv + 1 of a row, as bit 0 and bit 1.
unsigned two_bits(const std::uint64_t* row, std::int64_t iv) {
  const std::int64_t w = iv >> 6;
  const unsigned s = static_cast<unsigned>(iv & 63);
  std::uint64_t x = row[w] >> s;
  if (s == 63) x |= row[w + 1] << 1; // iv + 1 < samples per row, so the word exists
  return static_cast<unsigned>(x & 3u);
}

} // namespace

volume::Box cube_cells(const volume::Index3& shape) {
  return Box{{0, 0, 0}, {shape[0] - 1, shape[1] - 1, shape[2] - 1}};
}

LayerExtractor::Impl::Impl(const volume::Volume& vol, const Box& cells, const McOptions& opts)
    : volume(vol), box(cells), options(opts), lattice{vol.geometry().shape} {
  if (options.axis < 0 || options.axis > 2)
    throw InvalidArgument("marching cubes axis " + std::to_string(options.axis) + " is not 0, 1 or 2", {vol.source()},
                          "choose the extraction axis among 0 (i), 1 (j) and 2 (k)");
  if (std::isnan(options.iso))
    throw InvalidArgument("marching cubes iso value is NaN", {vol.source()}, "give a finite threshold");
  const Box all = cube_cells(lattice.shape);
  if (cells.empty() || all.empty() || !all.contains(cells))
    throw InvalidArgument("block of cells " + cells.to_string() + " is empty or not inside the cube's cells " +
                              all.to_string(),
                          {vol.source(), {}, {}, cells.to_string()},
                          "a block of cells [lo, hi) must lie within [0, n - 1) per axis of a cube of n samples");
  a = options.axis;
  u = a == 0 ? 1 : 0;
  v = a == 2 ? 1 : 2;
  nu = box.size(u);
  nv = box.size(v);
  su = nu + 1;
  sv = nv + 1;
  words = (sv + 63) / 64;
  rank = box.lo[a] + 1;
  slabs = std::make_unique<detail::SlabReader>(vol, Box{box.lo, {box.hi[0] + 1, box.hi[1] + 1, box.hi[2] + 1}}, a,
                                               options.slab_samples);
  const auto samples = static_cast<std::size_t>(su * sv);
  for (int s = 0; s < 2; ++s) {
    values[s].resize(samples);
    signs[s].resize(static_cast<std::size_t>(su * words));
  }
  for (auto& buffer : plane_slots)
    for (auto& slot : buffer)
      slot.resize(samples);
  across_slots.resize(samples);
  if (options.caps)
    for (auto& slot : sample_slots)
      slot.resize(samples);

  for (int e = 0; e < detail::kCellEdges; ++e) {
    const int c = detail::edge_start_corner(e), axis = detail::edge_axis(e);
    const int da = (c >> a) & 1;
    const auto du = static_cast<std::uint8_t>((c >> u) & 1), dv = static_cast<std::uint8_t>((c >> v) & 1);
    if (axis == a)
      edge_slot[e] = {across, du, dv};
    else if (axis == u)
      edge_slot[e] = {da ? b_u : a_u, du, dv};
    else
      edge_slot[e] = {da ? b_v : a_v, du, dv};
  }
  // Local corner L = dv + 2 du + 4 da (the order two_bits() assembles) to the cube-frame corner.
  for (int pattern = 0; pattern < 256; ++pattern) {
    int index = 0;
    for (int l = 0; l < 8; ++l)
      if ((pattern >> l) & 1) index |= 1 << ((((l >> 2) & 1) << a) | (((l >> 1) & 1) << u) | ((l & 1) << v));
    local_to_case[pattern] = static_cast<std::uint8_t>(index);
  }
}

void LayerExtractor::Impl::read(int which, std::int64_t section) {
  slabs->read(section, values[which]);
  // The low side compares the negated value with the negated iso: the same decisions as v <= iso.
  const float iso = options.below ? -options.iso : options.iso;
  const float sign = options.below ? -1.0f : 1.0f;
  for (std::int64_t iu = 0; iu < su; ++iu) {
    const float* row = values[which].data() + iu * sv;
    std::uint64_t* bits = signs[which].data() + iu * words;
    for (std::int64_t w = 0; w < words; ++w) {
      const std::int64_t begin = 64 * w, n = std::min<std::int64_t>(64, sv - begin);
      std::uint64_t word = 0;
      for (std::int64_t b = 0; b < n; ++b)
        word |= static_cast<std::uint64_t>(sign * row[begin + b] >= iso) << b;
      bits[w] = word;
    }
  }
}

std::uint32_t LayerExtractor::Impl::add_vertex(Layer& out, Index3 p0, int axis, float v0, float v1) const {
  double t = (static_cast<double>(options.iso) - static_cast<double>(v0)) /
             (static_cast<double>(v1) - static_cast<double>(v0));
  if (!(t >= kMcVertexMargin)) // also NaN (a NaN or infinite endpoint)
    t = kMcVertexMargin;
  else if (t > 1.0 - kMcVertexMargin)
    t = 1.0 - kMcVertexMargin;
  std::array<double, 3> p{static_cast<double>(p0[0]), static_cast<double>(p0[1]), static_cast<double>(p0[2])};
  p[axis] += t;
  const auto index = static_cast<std::uint32_t>(out.positions.size());
  out.positions.push_back(p);
  out.vertex_ids.push_back(lattice.id(p0[0], p0[1], p0[2], axis));
  // Along the sample axis: the run of inside samples ends (p0 inside) or starts (p0 + 1 inside).
  std::int64_t samples = 0;
  if (axis == 2) {
    const bool first_inside = options.below ? -v0 >= -options.iso : v0 >= options.iso;
    samples = first_inside ? p0[2] + 1 : -(p0[2] + 1);
  }
  out.vertex_samples.push_back(samples);
  return index;
}

void LayerExtractor::Impl::emit_plane(int which, Layer& out) {
  const std::int64_t section = rank - 1 + which;
  const float* val = values[which].data();
  const std::uint64_t* sg = signs[which].data();
  std::uint32_t* u_slot = plane_slots[which][0].data();
  std::uint32_t* v_slot = plane_slots[which][1].data();
  const auto first = static_cast<std::uint32_t>(out.positions.size());
  for (std::int64_t iu = 0; iu < nu; ++iu) // edges along u: rows iu and iu + 1 differ
    for (std::int64_t w = 0; w < words; ++w)
      for (std::uint64_t d = sg[iu * words + w] ^ sg[(iu + 1) * words + w]; d != 0; d &= d - 1) {
        const std::int64_t iv = 64 * w + std::countr_zero(d);
        u_slot[iu * sv + iv] =
            add_vertex(out, at(section, iu, iv), u, val[iu * sv + iv], val[(iu + 1) * sv + iv]) - first;
      }
  for (std::int64_t iu = 0; iu < su; ++iu) // edges along v: neighbouring bits of a row differ
    for (std::int64_t w = 0; w < words; ++w) {
      const std::uint64_t x = sg[iu * words + w];
      const std::uint64_t next = w + 1 < words ? sg[iu * words + w + 1] : 0;
      for (std::uint64_t d = (x ^ ((x >> 1) | (next << 63))) & mask_below(nv, w); d != 0; d &= d - 1) {
        const std::int64_t iv = 64 * w + std::countr_zero(d);
        v_slot[iu * sv + iv] =
            add_vertex(out, at(section, iu, iv), v, val[iu * sv + iv], val[iu * sv + iv + 1]) - first;
      }
    }
  if (options.caps) emit_samples(which, out, first);
}

void LayerExtractor::Impl::emit_across(Layer& out) {
  const auto first = static_cast<std::uint32_t>(out.positions.size());
  for (std::int64_t iu = 0; iu < su; ++iu)
    for (std::int64_t w = 0; w < words; ++w)
      for (std::uint64_t d = signs[0][iu * words + w] ^ signs[1][iu * words + w]; d != 0; d &= d - 1) {
        const std::int64_t iv = 64 * w + std::countr_zero(d);
        across_slots[iu * sv + iv] =
            add_vertex(out, at(rank - 1, iu, iv), a, values[0][iu * sv + iv], values[1][iu * sv + iv]) - first;
      }
}

void LayerExtractor::Impl::emit_triangles(Layer& out, const std::uint32_t (&base)[edge_array_count]) const {
  const std::uint32_t* slot[edge_array_count] = {plane_slots[0][0].data(), plane_slots[0][1].data(),
                                                 plane_slots[1][0].data(), plane_slots[1][1].data(),
                                                 across_slots.data()};
  const auto& cases = detail::mc_cases();
  auto sq = [&out](std::uint32_t p, std::uint32_t q) {
    const auto& x = out.positions[p];
    const auto& y = out.positions[q];
    return (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) + (x[2] - y[2]) * (x[2] - y[2]);
  };
  std::uint32_t vertex[detail::kCellEdges];
  for (std::int64_t iu = 0; iu < nu; ++iu) {
    const std::uint64_t* a0 = signs[0].data() + iu * words;
    const std::uint64_t* a1 = a0 + words;
    const std::uint64_t* b0 = signs[1].data() + iu * words;
    const std::uint64_t* b1 = b0 + words;
    for (std::int64_t w = 0; w < words; ++w) {
      // A cell iv needs a vertex unless its 8 corners (bits iv and iv + 1 of four rows) agree.
      const bool last = w + 1 == words;
      const std::uint64_t any = a0[w] | a1[w] | b0[w] | b1[w];
      const std::uint64_t all = a0[w] & a1[w] & b0[w] & b1[w];
      const std::uint64_t any_next = last ? 0 : a0[w + 1] | a1[w + 1] | b0[w + 1] | b1[w + 1];
      const std::uint64_t all_next = last ? 0 : a0[w + 1] & a1[w + 1] & b0[w + 1] & b1[w + 1];
      const std::uint64_t some_in = any | (any >> 1) | (any_next << 63);
      const std::uint64_t all_in = all & ((all >> 1) | (all_next << 63));
      for (std::uint64_t d = some_in & ~all_in & mask_below(nv, w); d != 0; d &= d - 1) {
        const std::int64_t iv = 64 * w + std::countr_zero(d);
        const unsigned pattern =
            two_bits(a0, iv) | (two_bits(a1, iv) << 2) | (two_bits(b0, iv) << 4) | (two_bits(b1, iv) << 6);
        const detail::McCase& c = cases[local_to_case[pattern]];
        for (int m = 0; m < c.edge_count; ++m) {
          const EdgeSlot& s = edge_slot[c.edges[m]];
          vertex[c.edges[m]] = base[s.array] + slot[s.array][(iu + s.du) * sv + iv + s.dv];
        }
        for (int m = 0; m < c.triangle_count; ++m) {
          const auto& t = c.triangles[m];
          out.triangles.push_back({vertex[t[0]], vertex[t[1]], vertex[t[2]]});
        }
        for (int m = 0; m < c.quad_count; ++m) {
          const auto& q = c.quads[m];
          const std::uint32_t p0 = vertex[q[0]], p1 = vertex[q[1]], p2 = vertex[q[2]], p3 = vertex[q[3]];
          if (sq(p0, p2) <= sq(p1, p3)) {
            out.triangles.push_back({p0, p1, p2});
            out.triangles.push_back({p0, p2, p3});
          } else {
            out.triangles.push_back({p1, p2, p3});
            out.triangles.push_back({p1, p3, p0});
          }
        }
      }
    }
  }
}

LayerExtractor::LayerExtractor(const volume::Volume& volume, const volume::Box& cells, const McOptions& options)
    : impl_(std::make_unique<Impl>(volume, cells, options)) {}

LayerExtractor::~LayerExtractor() = default;

bool LayerExtractor::next(Layer& out) {
  Impl& m = *impl_;
  out.clear();
  out.axis = m.a;
  if (m.rank > last_rank()) return false;
  if (!m.first_read) {
    m.read(0, m.rank - 1);
    m.first_read = true;
  }
  m.read(1, m.rank);
  out.rank = m.rank;
  if (m.have_kept) {
    out.vertex_ids = m.kept_ids;
    out.positions = m.kept_positions;
    out.vertex_samples = m.kept_samples;
  } else {
    m.emit_plane(0, out);
  }
  const auto b_first = static_cast<std::uint32_t>(out.positions.size());
  m.emit_plane(1, out);
  m.kept_ids.assign(out.vertex_ids.begin() + b_first, out.vertex_ids.end());
  m.kept_positions.assign(out.positions.begin() + b_first, out.positions.end());
  m.kept_samples.assign(out.vertex_samples.begin() + b_first, out.vertex_samples.end());
  m.have_kept = true;
  const auto across_first = static_cast<std::uint32_t>(out.positions.size());
  m.emit_across(out);
  const std::uint32_t base[edge_array_count] = {0, 0, b_first, b_first, across_first};
  m.emit_triangles(out, base);
  if (m.options.caps) m.emit_caps(out, b_first, across_first);
  std::swap(m.values[0], m.values[1]);
  std::swap(m.signs[0], m.signs[1]);
  std::swap(m.plane_slots[0], m.plane_slots[1]);
  std::swap(m.sample_slots[0], m.sample_slots[1]);
  ++m.rank;
  return true;
}

std::int64_t LayerExtractor::first_rank() const {
  return impl_->box.lo[impl_->a] + 1;
}
std::int64_t LayerExtractor::last_rank() const {
  return impl_->box.hi[impl_->a];
}
std::int64_t LayerExtractor::next_rank() const {
  return impl_->rank;
}
const volume::Box& LayerExtractor::cells() const {
  return impl_->box;
}
const LatticeIds& LayerExtractor::lattice() const {
  return impl_->lattice;
}

void release_slab_storage() {
  detail::SlabReader::release_spare();
}

} // namespace geotandem::tandem
