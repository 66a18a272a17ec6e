#pragma once
// A working surface as plain data: everything an engine needs to continue, with only the live
// elements, densely numbered. It is what the wire format (surface_wire.cpp) encodes and what a
// merge (surface_merge.cpp) welds; WorkingSurface::Engine exports and imports it.

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "geotandem/tandem/region.hpp"
#include "geotandem/tandem/simplify.hpp"
#include "geotandem/volume/geometry.hpp"
#include "working_mesh.hpp"

namespace geotandem::tandem::detail {

// An edge that is not idle, named by its endpoints (indices into SurfaceState::points), with its
// state and key and, for an edge in Q, what it keeps there (candidate, stamp, flags; zero
// otherwise).
struct StateEdge {
  std::uint32_t v0 = 0, v1 = 0;
  EdgeState state = EdgeState::idle;
  double key = 0.0;
  Pending pending;
};

// What a vertex carries in a state: its record without the sums over its current triangles
// (isotropy, cross and link sums), which follow from the triangles and are computed again when the
// state goes back into an engine (import_state, absorb_state). 128 bytes against the record's 216.
struct StateVertex {
  Quadric shape;
  double height = 0.0;
  double rad = 1.0;
  double tolerance = 0.0;
  std::uint64_t lattice_id = kNoLatticeId;
  std::int32_t component = -1; // an index into SurfaceState::component_keys
  std::uint32_t version = 0;
  std::uint8_t border = 0;
};
static_assert(sizeof(StateVertex) == 128, "a state vertex's size is counted in docs/algorithm.md (Memory)");

// The two ways between a vertex record and a state vertex, `component` numbered for the target.
inline StateVertex state_vertex(const VertexRecord& r, std::int32_t component) {
  return {.shape = r.shape,
          .height = r.height,
          .rad = r.rad,
          .tolerance = r.tolerance,
          .lattice_id = r.lattice_id,
          .component = component,
          .version = r.version,
          .border = r.border};
}
// A live record, its sums over its triangles still to be added.
inline VertexRecord vertex_record(const StateVertex& v, std::int32_t component) {
  VertexRecord r;
  r.shape = v.shape;
  r.height = v.height;
  r.rad = v.rad;
  r.tolerance = v.tolerance;
  r.lattice_id = v.lattice_id;
  r.component = component;
  r.version = v.version;
  r.border = v.border;
  r.alive = true;
  return r;
}

struct SurfaceState {
  volume::Geometry cube;
  Region region;
  int axis = 0;
  SimplifyOptions options;
  double front = 0.0;
  std::int64_t last_rank = 0;
  Vec3 origin{0.0, 0.0, 0.0};
  SimplifyCounters counters;

  std::vector<Vec3> points;
  std::vector<StateVertex> vertices; // per vertex
  // Oriented outward, into points; the first corner is the one the face's terms start from
  // (working_mesh.hpp, FaceRecord).
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<StateEdge> edges;
  // The key (smallest lattice id ever born in it) of every live component.
  std::vector<std::uint64_t> component_keys;
  // The samples each encloses so far (ComponentRecord::samples); empty in records written before
  // they were counted (all 0).
  std::vector<std::int64_t> component_samples;
  // Lattice id -> vertex for the last layer (the next layer may repeat them), and vertices of the
  // last layer that no triangle uses yet. Both empty after the sweep.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> previous_ids;
  std::vector<std::uint32_t> isolated;
};

} // namespace geotandem::tandem::detail
