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
inline constexpr std::uint32_t kSurfaceWireVersion = 1;
// Size of the fixed header in front of the payload: magic (8 bytes), version (4), flags (4),
// payload length (8), XXH64 of the payload (8).
inline constexpr std::size_t kSurfaceWireHeaderSize = 32;

// The surface as a record. The surface is not changed. Works at any point of the sweep (between
// layers) as well as after it.
std::vector<std::byte> serialize(const WorkingSurface& surface);

// A surface that continues exactly where the serialized one stood; finished components go to
// `sink` (may be null), collapses to `observer` (may be null). Throws DataError naming the problem
// when the record is not a working-surface record, has another format version, is truncated or
// longer than its header says, fails its checksum, or holds an inconsistent surface.
WorkingSurface deserialize(std::span<const std::byte> record, mesh::ComponentSink* sink,
                           CollapseObserver* observer = nullptr);

} // namespace geotandem::tandem
