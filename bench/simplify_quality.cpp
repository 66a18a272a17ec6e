// Quality of the tandem against the full-resolution marching-cubes surface, over E0 and alpha, on
// analytic bodies: triangles kept, enclosed volume, distances, anisotropy. The figures behind the
// defaults in docs/algorithm.md.
//
//   bench_simplify_quality [radius=11] [E0 list=0.1,0.2,0.3,0.5] [alpha list=0,0.4,1]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "geotandem/mesh/quality.hpp"
#include "geotandem/mesh/topology.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "geotandem/tandem/tandem.hpp"
#include "geotandem/volume/volume.hpp"

using namespace geotandem;

namespace {

class Collect final : public mesh::ComponentSink {
public:
  void commit(const mesh::Component& c) override {
    const auto base = static_cast<std::uint32_t>(all.points.size());
    all.points.insert(all.points.end(), c.surface.points.begin(), c.surface.points.end());
    for (const auto& t : c.surface.triangles)
      all.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    ++count;
  }
  mesh::SurfaceMesh all;
  int count = 0;
};

} // namespace

int bench_main(int argc, char** argv) {
  const geotandem::bench::Args args(
      argc, argv, "bench_simplify_quality [radius=11] [E0 list=0.1,0.2,0.3,0.5] [alpha list=0,0.4,1]");
  const double radius = args.real(1, 11.0, 1.0);
  const std::vector<double> errors = args.reals(2, "0.1,0.2,0.3,0.5", 0.0);
  const std::vector<double> alphas = args.reals(3, "0,0.4,1", 0.0);
  const auto n = static_cast<std::int64_t>(2 * radius + 10);
  volume::Geometry g;
  g.shape = {n, n + 1, n + 2};
  std::vector<float> samples(g.bounds().count());
  const double c[3] = {0.5 * static_cast<double>(n) + 0.31, 0.5 * static_cast<double>(n) + 0.17,
                       0.5 * static_cast<double>(n) - 0.23};
  for (std::int64_t i = 0; i < g.shape[0]; ++i)
    for (std::int64_t j = 0; j < g.shape[1]; ++j)
      for (std::int64_t k = 0; k < g.shape[2]; ++k) {
        // An ellipsoid with semi-axes radius, 0.8 radius, 0.6 radius (signed distance-like field).
        const double x = (static_cast<double>(i) - c[0]) / radius, y = (static_cast<double>(j) - c[1]) / (0.8 * radius),
                     z = (static_cast<double>(k) - c[2]) / (0.6 * radius);
        samples[g.bounds().offset({i, j, k})] =
            static_cast<float>(0.3 * radius * (1.0 - std::sqrt(x * x + y * y + z * z)));
      }
  volume::MemoryVolume volume(g, samples);
  const volume::Box cells = tandem::cube_cells(g.shape);
  const mesh::SurfaceMesh full = tandem::extract_surface(volume, cells, {0.0f, 0});
  const double full_volume = mesh::enclosed_volume(full);
  std::printf(
      "ellipsoid semi-axes %.1f %.1f %.1f voxels: %zu full-resolution triangles, volume %.1f, anisotropy %.3f\n",
      radius, 0.8 * radius, 0.6 * radius, full.triangle_count(), full_volume, mesh::anisotropy(full));
  std::printf("%6s %5s %8s %7s %9s %8s %8s %7s %7s\n", "E0", "alpha", "tris", "kept%", "vol-err%", "d.max", "d.rms",
              "aniso", "closed");
  for (double e0 : errors)
    for (double alpha : alphas) {
      tandem::TandemOptions options;
      options.simplify.max_error = e0;
      options.simplify.isotropy = alpha;
      Collect sink;
      tandem::extract_block(volume, cells, options, &sink);
      const mesh::DistanceStats d = mesh::hausdorff_distance(sink.all, full);
      const bool closed = mesh::check_topology(sink.all).is_closed_manifold();
      std::printf("%6.3f %5.2f %8zu %7.2f %9.3f %8.3f %8.3f %7.3f %7s\n", e0, alpha, sink.all.triangle_count(),
                  100.0 * static_cast<double>(sink.all.triangle_count()) / static_cast<double>(full.triangle_count()),
                  100.0 * (mesh::enclosed_volume(sink.all) / full_volume - 1.0), d.max, d.rms,
                  mesh::anisotropy(sink.all), closed ? "yes" : "NO");
    }
  return 0;
}

int main(int argc, char** argv) {
  return geotandem::bench::guarded_main("bench_simplify_quality", [&] { return bench_main(argc, argv); });
}
