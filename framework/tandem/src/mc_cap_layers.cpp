// The caps of LayerExtractor (marching_cubes.hpp): the inside samples on the cube's border get
// vertices of their own, and the squares of the border faces that hold them are triangulated
// (mc_caps.hpp), so that bodies cut by the border come out closed.
#include "layer_extractor_impl.hpp"
#include "mc_caps.hpp"

namespace geotandem::tandem {

using volume::Index3;

void LayerExtractor::Impl::emit_samples(int which, Layer& out, std::uint32_t first) {
  const std::int64_t section = rank - 1 + which;
  const Index3& n = lattice.shape;
  const bool whole = section == 0 || section == n[a] - 1;
  const bool v_lo = box.lo[v] == 0, v_hi = box.lo[v] + nv == n[v] - 1;
  std::uint32_t* slot = sample_slots[which].data();
  auto add = [&](std::int64_t iu, std::int64_t iv) {
    if (!inside(which, iu, iv)) return;
    const Index3 g = at(section, iu, iv);
    slot[iu * sv + iv] = static_cast<std::uint32_t>(out.positions.size()) - first;
    out.positions.push_back({static_cast<double>(g[0]), static_cast<double>(g[1]), static_cast<double>(g[2])});
    out.vertex_ids.push_back(lattice.sample_id(g[0], g[1], g[2]));
    out.vertex_samples.push_back(g[2] == n[2] - 1 ? n[2] : 0); // a run of inside samples ends at the last plane
  };
  for (std::int64_t iu = 0; iu < su; ++iu) {
    const std::int64_t gu = box.lo[u] + iu;
    if (whole || gu == 0 || gu == n[u] - 1) {
      for (std::int64_t iv = 0; iv < sv; ++iv)
        add(iu, iv);
    } else {
      if (v_lo) add(iu, 0);
      if (v_hi) add(iu, nv);
    }
  }
}

void LayerExtractor::Impl::emit_caps(Layer& out, std::uint32_t b_first, std::uint32_t across_first) const {
  const Index3& n = lattice.shape;
  const std::uint32_t first[2] = {0, b_first};
  auto at_uv = [this](std::int64_t iu, std::int64_t iv) { return static_cast<std::size_t>(iu * sv + iv); };
  auto corner = [&](detail::CapSquare& q, int c, int which, std::int64_t iu, std::int64_t iv) {
    q.inside[c] = inside(which, iu, iv);
    if (q.inside[c]) q.corner[c] = first[which] + sample_slots[which][at_uv(iu, iv)];
  };
  // Edge vertices are looked up only where the signs of their ends differ (they exist there).
  auto along = [&](int which, int dir, std::int64_t iu, std::int64_t iv) {
    return first[which] + plane_slots[which][dir][at_uv(iu, iv)];
  };
  auto across_at = [&](std::int64_t iu, std::int64_t iv) { return across_first + across_slots[at_uv(iu, iv)]; };
  auto emit = [&](detail::CapSquare& q, auto&& edge, int axis, int side) {
    for (int c = 0; c < 4; ++c)
      if (q.inside[c] != q.inside[(c + 1) % 4]) q.edge[c] = edge(c);
    detail::emit_cap_square(q, axis, side, out);
  };
  // Faces across u and v: squares between cross-sections A and B.
  for (int side = 0; side < 2; ++side) {
    if (side == 0 ? box.lo[u] == 0 : box.lo[u] + nu == n[u] - 1) {
      const std::int64_t iu = side == 0 ? 0 : nu;
      for (std::int64_t iv = 0; iv < nv; ++iv) {
        detail::CapSquare q;
        corner(q, 0, 0, iu, iv);
        corner(q, 1, 0, iu, iv + 1);
        corner(q, 2, 1, iu, iv + 1);
        corner(q, 3, 1, iu, iv);
        emit(
            q,
            [&](int c) {
              return c == 0   ? along(0, 1, iu, iv)
                     : c == 1 ? across_at(iu, iv + 1)
                     : c == 2 ? along(1, 1, iu, iv)
                              : across_at(iu, iv);
            },
            u, side);
      }
    }
    if (side == 0 ? box.lo[v] == 0 : box.lo[v] + nv == n[v] - 1) {
      const std::int64_t iv = side == 0 ? 0 : nv;
      for (std::int64_t iu = 0; iu < nu; ++iu) {
        detail::CapSquare q;
        corner(q, 0, 0, iu, iv);
        corner(q, 1, 0, iu + 1, iv);
        corner(q, 2, 1, iu + 1, iv);
        corner(q, 3, 1, iu, iv);
        emit(
            q,
            [&](int c) {
              return c == 0   ? along(0, 0, iu, iv)
                     : c == 1 ? across_at(iu + 1, iv)
                     : c == 2 ? along(1, 0, iu, iv)
                              : across_at(iu, iv);
            },
            v, side);
      }
    }
  }
  // Faces across the extraction axis: the whole first or last cross-section of the cube.
  for (int which = 0; which < 2; ++which) {
    if (rank - 1 + which != (which == 0 ? 0 : n[a] - 1)) continue;
    for (std::int64_t iu = 0; iu < nu; ++iu)
      for (std::int64_t iv = 0; iv < nv; ++iv) {
        detail::CapSquare q;
        corner(q, 0, which, iu, iv);
        corner(q, 1, which, iu + 1, iv);
        corner(q, 2, which, iu + 1, iv + 1);
        corner(q, 3, which, iu, iv + 1);
        if (!q.inside[0] && !q.inside[1] && !q.inside[2] && !q.inside[3]) continue;
        emit(
            q,
            [&](int c) {
              return c == 0   ? along(which, 0, iu, iv)
                     : c == 1 ? along(which, 1, iu + 1, iv)
                     : c == 2 ? along(which, 0, iu, iv + 1)
                              : along(which, 1, iu, iv);
            },
            a, which);
      }
  }
}

} // namespace geotandem::tandem
