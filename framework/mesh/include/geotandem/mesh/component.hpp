#pragma once
// A finished surface component as the tandem algorithm hands it over, its measures, and the sink
// interface through which it leaves the algorithm (the store implements it; tests can collect).

#include <array>
#include <cstdint>
#include <string>

#include "geotandem/mesh/surface.hpp"

namespace geotandem::mesh {

// Measures of one component. Lengths, areas and volumes are in world units (metres horizontally;
// the sample axis in its own unit: ms or m), so a volume is m^3 for depth cubes and m^2*ms for
// time cubes. Angles in degrees.
struct ComponentStats {
  std::uint64_t vertex_count = 0;
  std::uint64_t triangle_count = 0;
  bool closed = false;        // every edge has exactly two triangles (no border)
  bool cut_by_border = false; // the cube's outer faces cut it (cut_faces != 0)
  // Which outer faces of the cube cut it: bit 2 * axis + side (side 0: index 0, 1: index n - 1),
  // i.e. i- i+ j- j+ k- k+ for bits 0..5 (cut_faces_text). A cut body is closed by caps on those
  // planes (docs/caps.md); cap_area is their part of `area`.
  std::uint8_t cut_faces = 0;
  double cap_area = 0.0;
  double volume = 0.0; // enclosed volume by the divergence theorem; 0 when not closed
  // The volume in samples (issue 54): the samples on the body's side of iso that the full-resolution
  // marching-cubes surface encloses, counted exactly along the traces as the surface is extracted
  // (tandem::Layer::vertex_samples). Like `volume` a cavity's surface counts negative; a body's
  // outer surface counts its cavities' samples too. 0 for sources that do not count (caps off: an
  // open body's count is meaningless).
  std::int64_t samples = 0;
  double area = 0.0;
  std::array<double, 3> centroid{}; // area-weighted centroid of the surface, world x, y, z
  std::array<double, 3> box_min{};  // axis-aligned bounds in world coordinates
  std::array<double, 3> box_max{};
  // Oriented bounding box from the principal axes of the surface (area-weighted covariance):
  // axes[0] is the longest. Half extents along each axis.
  std::array<double, 3> obb_center{};
  std::array<std::array<double, 3>, 3> obb_axes{};
  std::array<double, 3> obb_half_extents{};
  double azimuth = 0.0;    // of the main horizontal axis, clockwise from north, axial: [0, 180)
  double dip = 0.0;        // of the main axis below the horizontal, [0, 90]
  double elongation = 0.0; // 1 - (second extent / first extent) of the horizontal footprint, [0, 1]
};

// "i-,k+" for the bits of ComponentStats::cut_faces ("" when none), and back. Parsing throws
// InvalidArgument on anything else.
std::string cut_faces_text(std::uint8_t faces);
std::uint8_t parse_cut_faces(const std::string& text);

// A finished component, in index coordinates (voxel units) as the algorithm works.
struct Component {
  // Deterministic identity: the smallest global lattice-edge id of any marching-cubes vertex ever
  // born in this component. The same body gets the same key whatever the block decomposition and
  // the number of workers, so a component committed twice is stored once.
  std::uint64_t key = 0;
  SurfaceMesh surface;
  ComponentStats stats;
};

// Where finished components go. commit() must be idempotent per key.
class ComponentSink {
public:
  virtual ~ComponentSink() = default;
  virtual void commit(const Component& component) = 0;
};

} // namespace geotandem::mesh
