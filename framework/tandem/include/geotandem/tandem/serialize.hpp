#pragma once
// The wire form of a partial surface: what a worker ships to another for a merge, and what a
// checkpoint keeps. A versioned, checksummed binary record holding everything needed to continue
// (the cube's geometry, the region, the axis, the options, the front, the counters, the mesh with
// its quadrics, heights, radii and lattice ids, the queues' states, the components). Layout:
// docs/algorithm.md, "The wire format".
//
// Byte order: little-endian (the record says so in its magic; a big-endian host refuses it).

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "geotandem/mesh/component.hpp"
#include "geotandem/tandem/simplify.hpp"

namespace geotandem::tandem {

// Version of the record this build writes and reads.
// 2: per-vertex distance bounds (E0 guarantee); 3: triangles without their terms (computed again);
// 4: vertices without W_v, the determinant sum and the normal sum (they follow from the others);
// 5: vertices without their sums over their triangles (computed again from the triangles).
inline constexpr std::uint32_t kSurfaceWireVersion = 5;
// Header flag: the payload ends with the samples each component encloses so far (issue 54), one
// int64 per component after a count. Records without it (older writers) read as 0 samples.
inline constexpr std::uint32_t kFlagComponentSamples = 1;
// Size of the fixed header in front of the payload: magic (8 bytes), version (4), flags (4),
// payload length (8), XXH64 of the payload (8).
inline constexpr std::size_t kSurfaceWireHeaderSize = 32;

// The surface as a record. The surface is not changed. Works at any point of the sweep (between
// layers) as well as after it.
std::vector<std::byte> serialize(const WorkingSurface& surface);
// The same, for a surface that is not needed afterwards: its storage is given back before the
// record is built (the surface is left empty, as after a move).
std::vector<std::byte> serialize(WorkingSurface&& surface);

// A surface that continues exactly where the serialized one stood; finished components go to
// `sink` (may be null), collapses to `observer` (may be null). Throws DataError naming the problem
// when the record is not a working-surface record, has another format version, is truncated or
// longer than its header says, fails its checksum, or holds a surface that breaks what the engine
// relies on (a valid checksum does not make a record trusted: docs/algorithm.md, "What a record
// must satisfy"; the message's context names the record's blocks).
WorkingSurface deserialize(std::span<const std::byte> record, mesh::ComponentSink* sink,
                           CollapseObserver* observer = nullptr);

// WorkingSurface::merge with the other side given as its record: the record is decoded straight
// into `into` (no surface engine is built for the sender), welded, the seam simplified, finished
// components dumped to `into`'s sink. Returns the number dumped. `into` always takes in the
// record, whatever their sizes. Throws DataError for a bad record (as deserialize) or surfaces that
// do not fit together (the regions, a welded vertex's position or place, a seam edge's direction:
// nothing changed then), DataError when a triangle still cannot be welded in (then `into` is in an
// unspecified state: drop it), and Cancelled.
std::size_t merge_record(WorkingSurface& into, std::span<const std::byte> record, const CancelToken* cancel = nullptr);
// The same, giving the record's storage back once it is decoded, before `into` grows.
std::size_t merge_record(WorkingSurface& into, std::vector<std::byte>&& record, const CancelToken* cancel = nullptr);

} // namespace geotandem::tandem
