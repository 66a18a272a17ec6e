#pragma once
// Marching cubes made for stitching (ALGORITHM.md, "Marching cubes, made for stitching"): layer by
// layer along one index axis, holding at most two cross-sections of samples, with a case table
// whose ambiguous faces are decided by the face's own four corner signs. Two blocks that share a
// sample plane produce the same vertices (same lattice-edge ids, bit-identical positions) and the
// same segments on it, so welding by id gives exactly the surface of one block covering both.
// See docs/marching-cubes.md for the rule and its consequences.
//
// Units: every coordinate is in index units (i, j, k) of the whole cube, spacing 1.
// Inside means value >= iso (McOptions::below: value <= iso; NaN samples are outside either way).
// Triangles are counter-clockwise seen from outside, so a closed body has a positive enclosed volume.

#include <cstdint>
#include <memory>
#include <vector>

#include "geotandem/mesh/surface.hpp"
#include "geotandem/tandem/layer.hpp"
#include "geotandem/volume/box.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::tandem {

// A vertex never lies closer than this (as a fraction of the lattice edge) to a sample: values
// equal to iso would otherwise put vertices on samples, where several lattice edges would give
// coincident vertices and zero-area triangles. The shift is at most 1/256 of a voxel.
inline constexpr double kMcVertexMargin = 1.0 / 256.0;

// The default budget of one slab of cross-sections read at once (samples; 32 MiB of floats).
inline constexpr std::int64_t kMcSlabSamples = std::int64_t{1} << 23;

struct McOptions {
  float iso = 0.0f; // threshold; must not be NaN
  int axis = 0;     // extraction axis (0 = i, 1 = j, 2 = k): the layers are stacked along it
  // Cross-sections are read from the volume in slabs of as many consecutive sections as fit in
  // this many samples (at least one): a computed volume then pays its halo once per slab, not
  // once per section; a slab holds at least 8 times the volume's halo along the axis
  // (Volume::source_halo) when that fits in 4 budgets. Values and surfaces do not depend on it.
  std::int64_t slab_samples = kMcSlabSamples;
  // Close bodies cut by the cube's border with caps on its outer sample planes (docs/caps.md):
  // each inside sample on an outer plane becomes a vertex (LatticeIds::sample_id) and each square
  // of samples on an outer plane contributes the inside part of it, bounded by the same edge
  // vertices as the body, so the surface is a closed 2-manifold everywhere. Off: open borders.
  bool caps = true;
  // The low side (issue 54): inside means value <= iso. Exactly the surface of the negated cube at
  // -iso: the sign bits are those of -value >= -iso (ties inside), and a vertex's t is
  // (iso - v0) / (v1 - v0) either way (negation is exact in IEEE arithmetic), so ids, positions,
  // connectivity (6-adjacency of the inside) and orientation (normals out of the body, towards
  // values above iso) are the negated cube's. Kept last so that aggregate initialisers of the
  // fields above keep their meaning.
  bool below = false;
};

// The cells of a whole cube of `shape` samples: [0, n - 1) per axis. A cell (i, j, k) spans the
// samples i..i+1, j..j+1, k..k+1.
volume::Box cube_cells(const volume::Index3& shape);

// Extracts the layers of one block of cells, in increasing rank.
// A block of cells [lo, hi) reads samples [lo, hi + 1); layer k (rank k) holds its cells whose
// index along the axis is k - 1, between cross-sections k - 1 and k, for k = lo + 1 .. hi.
// Each cross-section is read once, in slabs of consecutive cross-sections (McOptions::slab_samples);
// besides the slab, never more than two are held. Vertices carry the global lattice-edge ids of the whole cube
// (LatticeIds of the volume's shape) and positions computed from the edge's lower-index end:
//   t = (iso - v0) / (v1 - v0), clamped to [kMcVertexMargin, 1 - kMcVertexMargin],
// so every block and every axis computes bit-identical vertices.
// Throws InvalidArgument when the options are invalid or `cells` is empty or not inside the
// cube's cells; read errors of the volume (IoError, FormatError, ...) pass through.
// Memory: about 30 bytes per sample of one cross-section of the block (two cross-sections of
// values, their sign bits, vertex numbers per lattice edge), plus one slab and the layer's output.
// The volume must outlive the extractor; one extractor per thread. An extractor takes over the
// slab storage the last one on its thread left, so that block after block reuses the same pages
// (release_slab_storage() gives them back).
class LayerExtractor {
public:
  LayerExtractor(const volume::Volume& volume, const volume::Box& cells, const McOptions& options);
  ~LayerExtractor();
  LayerExtractor(const LayerExtractor&) = delete;
  LayerExtractor& operator=(const LayerExtractor&) = delete;

  // Fills `out` (cleared first) with the next layer; false once every layer was returned.
  // Order guarantee: layer k lists first its vertices on cross-section k - 1, in the order layer
  // k - 1 listed them (there as one contiguous run); a consumer may weld by that order.
  bool next(Layer& out);

  std::int64_t first_rank() const; // cells.lo[axis] + 1
  std::int64_t last_rank() const;  // cells.hi[axis]
  std::int64_t next_rank() const;  // the rank the next call to next() returns (last_rank() + 1 at the end)
  const volume::Box& cells() const;
  const LatticeIds& lattice() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Gives back the slab storage kept on the calling thread for its next LayerExtractor (at most one
// slab: the largest a block read there). For a driver about to need the memory more, e.g. before a
// large merge; the next extractor allocates its slab again.
void release_slab_storage();

// The whole surface of a block of cells in one mesh, vertices welded by lattice-edge id (the
// oracle for tests and the "brute" route). `ids`, when given, receives the lattice-edge id of
// each point. Same preconditions and errors as LayerExtractor.
mesh::SurfaceMesh extract_surface(const volume::Volume& volume, const volume::Box& cells, const McOptions& options,
                                  std::vector<std::uint64_t>* ids = nullptr);

} // namespace geotandem::tandem
