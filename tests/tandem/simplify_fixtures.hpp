#pragma once
// Fixtures for the simplifier tests: analytic fields, an independent layer source (marching
// tetrahedra over the Kuhn subdivision of every cell: always a closed, consistently oriented
// 2-manifold, with no ambiguous case), and a sink that keeps what it receives.

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "geotandem/mesh/component.hpp"
#include "geotandem/tandem/layer.hpp"
#include "geotandem/tandem/simplify.hpp"
#include "geotandem/tandem/tandem.hpp"
#include "geotandem/volume/box.hpp"
#include "geotandem/volume/geometry.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::tandem::fixtures {

// A scalar field of sample indices; inside means value >= iso.
using Field = std::function<double(double i, double j, double k)>;

Field sphere(std::array<double, 3> centre, double radius);
Field ellipsoid(std::array<double, 3> centre, std::array<double, 3> radii);
Field torus(std::array<double, 3> centre, double major, double minor); // in the (i, j) plane
// max of the given fields (a union of bodies)
Field union_of(std::vector<Field> fields);

// A geometry of `shape` samples, 25 m bins, 4 ms samples.
volume::Geometry test_geometry(const volume::Index3& shape);

// Layers of marching tetrahedra over `cells` (a box of cells of a cube of `shape` samples), along
// `axis`. Vertex ids: 7 * sample index + (direction - 1), direction a bit mask of +i, +j, +k, for
// the lattice edges and diagonals of the Kuhn subdivision.
class TetraLayers final : public LayerSource {
public:
  TetraLayers(Field field, volume::Index3 shape, volume::Box cells, double iso, int axis);
  bool next(Layer& layer) override;

private:
  std::vector<double> values_; // the field at every sample of the cells' box (evaluated once)
  volume::Box samples_;
  volume::Index3 shape_;
  volume::Box cells_;
  double iso_;
  int axis_;
  std::int64_t next_rank_;
};

// Which extraction feeds a test: the project's marching cubes (the production path, fewer
// triangles) or the independent marching tetrahedra above (another triangulation, more slivers).
enum class Mesher { marching_cubes, tetrahedra };
const char* to_string(Mesher m);

// A field sampled once on a cube, with its layers and its full-resolution oracle.
class Input {
public:
  Input(Field field, volume::Index3 shape, Mesher mesher = Mesher::marching_cubes);
  const volume::Index3& shape() const { return shape_; }
  volume::Box cells() const; // the whole cube's cells
  std::unique_ptr<LayerSource> layers(const volume::Box& cells, int axis) const;
  // The whole surface of `cells` welded by id; `ids` receives the lattice id of every point.
  mesh::SurfaceMesh full(const volume::Box& cells, int axis, std::vector<std::uint64_t>* ids = nullptr) const;

private:
  Field field_;
  volume::Index3 shape_;
  Mesher mesher_;
  std::unique_ptr<volume::MemoryVolume> volume_;
};

// The whole surface of `cells`, welded by id (the full-resolution oracle). `ids` receives the id of
// every point when given.
mesh::SurfaceMesh tetra_surface(const Field& field, const volume::Index3& shape, const volume::Box& cells, double iso,
                                int axis, std::vector<std::uint64_t>* ids = nullptr);

// Keeps every component; records how many layers had been seen when each arrived.
class CollectingSink final : public mesh::ComponentSink {
public:
  void commit(const mesh::Component& component) override;
  std::vector<mesh::Component> components;
  std::vector<std::int64_t> commit_front;  // the surface's front when each component arrived
  const WorkingSurface* surface = nullptr; // to read the front from, when set
};

// Every surface of a list merged into one (re-indexed).
mesh::SurfaceMesh concatenate(const std::vector<mesh::Component>& components);

// Records every collapse event.
class RecordingObserver final : public CollapseObserver {
public:
  void on_collapse(const CollapseEvent& event) override { events.push_back(event); }
  std::vector<CollapseEvent> events;
};

} // namespace geotandem::tandem::fixtures
