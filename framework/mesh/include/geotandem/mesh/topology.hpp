#pragma once
// Topological checks of a triangle surface: the invariants every extracted or simplified surface
// must keep (closed, consistently oriented 2-manifold where it does not leave the cube).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "geotandem/mesh/surface.hpp"

namespace geotandem::mesh {

struct TopologyReport {
  std::size_t vertices = 0; // referenced vertices
  std::size_t triangles = 0;
  std::size_t components = 0;            // connected through shared edges or vertices
  std::size_t boundary_edges = 0;        // edges with one triangle
  std::size_t non_manifold_edges = 0;    // edges with three or more triangles
  std::size_t non_manifold_vertices = 0; // vertices whose triangle fan is not one disc/half-disc
  std::size_t misoriented_edges = 0;     // interior edges used twice in the same direction
  std::size_t degenerate_triangles = 0;  // repeated vertex index, or zero area
  std::size_t unreferenced_vertices = 0;
  long euler_characteristic = 0; // V - E + F over referenced vertices

  bool is_manifold() const { return non_manifold_edges == 0 && non_manifold_vertices == 0; }
  bool is_closed_manifold() const { return is_manifold() && boundary_edges == 0 && misoriented_edges == 0; }
  // One line, for test failure messages.
  std::string summary() const;
};

// Linear in the size of the surface (vertex stars by counting sort; no map of vertex pairs).
// A triangle with a repeated vertex index counts as degenerate and is otherwise left out: it adds
// no edge, no face and references no vertex. A zero-area triangle (collinear up to rounding) with
// three distinct indices counts as degenerate and still takes part in the topology. A vertex on a
// non-manifold edge usually also counts as a non-manifold vertex (when its fans meet only through
// that edge).
// Throws InvalidArgument when a triangle refers to a vertex that does not exist.
TopologyReport check_topology(const SurfaceMesh& surface);

// Splits a surface into its connected components (through shared vertices), each re-indexed.
// Deterministic: components come in the order of their smallest vertex index, and vertices and
// triangles keep their relative order. Unreferenced vertices are dropped. Throws InvalidArgument
// on an out-of-range vertex index.
std::vector<SurfaceMesh> split_components(const SurfaceMesh& surface);

// Merges vertices that carry the same key (for example a lattice-edge id) and drops unused ones.
// The first point (lowest index) of each key is kept; kept points stay in their relative order.
// Triangles are kept as they are, even one that welding makes degenerate (check_topology reports
// it). Throws InvalidArgument when keys and points differ in number or an index is out of range.
SurfaceMesh weld_by_key(const std::vector<Point>& points, const std::vector<std::uint64_t>& keys,
                        const std::vector<Triangle>& triangles);

} // namespace geotandem::mesh
