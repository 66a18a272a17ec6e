// Marching-cubes throughput on one core: cells/s, triangles/s and triangles for generated fields
// (Gaussian blobs plus noise, a smooth field, an empty field), layer by layer and welded.
//
// Usage: bench_mc_throughput [n (default 256)] [repeats (default 3)] [field (blobs, smooth, empty;
// default all)] [axis (0, 1, 2; default all)]
// Prints the best of `repeats` runs per field, timed in CPU seconds of the running thread (the
// figure per core, robust when other processes share the machine) and in wall seconds. Axis 2 is the fastest axis of
// the in-memory cube: its cross-sections are strided gathers, which is why extraction runs along the slowest axis.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "geotandem/volume/volume.hpp"

namespace {

using geotandem::volume::Index3;
using geotandem::volume::MemoryVolume;

MemoryVolume make_volume(std::int64_t n, std::vector<float> samples) {
  geotandem::volume::Geometry g;
  g.shape = {n, n, n};
  return MemoryVolume(g, std::move(samples), "bench field");
}

// Many small Gaussian blobs and uniform noise: lots of small components, ~1 M triangles at 256^3.
std::vector<float> blobs(std::int64_t n) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> pos(0.0f, static_cast<float>(n)), width(1.5f, 4.0f), noise(-0.08f, 0.08f);
  std::vector<float> f(static_cast<std::size_t>(n * n * n), 0.0f);
  const int count = static_cast<int>(2000 * (n * n * n) / (256.0 * 256.0 * 256.0)) + 1;
  for (int b = 0; b < count; ++b) {
    const float ci = pos(rng), cj = pos(rng), ck = pos(rng), s = width(rng);
    const std::int64_t r = static_cast<std::int64_t>(std::ceil(3 * s));
    for (std::int64_t i = std::max<std::int64_t>(0, static_cast<std::int64_t>(ci) - r);
         i < std::min<std::int64_t>(n, static_cast<std::int64_t>(ci) + r + 1); ++i)
      for (std::int64_t j = std::max<std::int64_t>(0, static_cast<std::int64_t>(cj) - r);
           j < std::min<std::int64_t>(n, static_cast<std::int64_t>(cj) + r + 1); ++j)
        for (std::int64_t k = std::max<std::int64_t>(0, static_cast<std::int64_t>(ck) - r);
             k < std::min<std::int64_t>(n, static_cast<std::int64_t>(ck) + r + 1); ++k) {
          const float d2 = (i - ci) * (i - ci) + (j - cj) * (j - cj) + (k - ck) * (k - ck);
          f[static_cast<std::size_t>((i * n + j) * n + k)] += std::exp(-d2 / (2 * s * s));
        }
  }
  for (float& x : f)
    x += noise(rng);
  return f;
}

// A few large smooth undulating surfaces (horizon-like), no noise.
std::vector<float> smooth(std::int64_t n) {
  std::vector<float> f(static_cast<std::size_t>(n * n * n));
  const double w = 2 * 3.14159265358979 / static_cast<double>(n);
  for (std::int64_t i = 0; i < n; ++i)
    for (std::int64_t j = 0; j < n; ++j)
      for (std::int64_t k = 0; k < n; ++k)
        f[static_cast<std::size_t>((i * n + j) * n + k)] =
            static_cast<float>(std::sin(w * 2 * i) * std::cos(w * 3 * j) + std::sin(w * 4 * k));
  return f;
}

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Run {
  double seconds = 1e300; // CPU
  double wall = 0;
  std::size_t triangles = 0;
};

template <class F> Run best_of(int repeats, F&& f) {
  Run best;
  for (int r = 0; r < repeats; ++r) {
    const double c0 = thread_cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    const std::size_t triangles = f();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double s = thread_cpu_seconds() - c0;
    if (s < best.seconds) best = {s, wall, triangles};
  }
  return best;
}

void report(const char* field, const char* mode, int axis, std::int64_t n, const Run& r) {
  const double cells = static_cast<double>((n - 1) * (n - 1) * (n - 1));
  std::printf("%-7s %-7s axis %d %8.1f M cells/s %7.2f M triangles/s %9zu triangles %7.3f s cpu %7.3f s wall\n", field,
              mode, axis, cells / r.seconds / 1e6, static_cast<double>(r.triangles) / r.seconds / 1e6, r.triangles,
              r.seconds, r.wall);
}

} // namespace

int bench_main(int argc, char** argv) {
  const geotandem::bench::Args args(argc, argv,
                                    "bench_mc_throughput [n=256] [repeats=3] [field: blobs, smooth or empty; default "
                                    "all] [axis: 0, 1 or 2; default all]");
  const std::int64_t n = args.integer(1, 256, 2);
  const auto repeats = static_cast<int>(args.integer(2, 3, 1));
  const std::string only_field = args.has(3) ? args.word(3, "", {"blobs", "smooth", "empty"}) : "";
  const auto only_axis = static_cast<int>(args.integer(4, -1, 0));
  if (only_axis > 2) args.fail(4, "is not an axis (0, 1 or 2)");
  std::printf("marching cubes, one thread, %lld^3 samples (%lld^3 cells), best of %d\n", static_cast<long long>(n),
              static_cast<long long>(n - 1), repeats);
  struct Field {
    const char* name;
    MemoryVolume volume;
    float iso;
  };
  std::vector<Field> fields;
  auto wanted = [&](const char* name) { return only_field.empty() || only_field == name; };
  if (wanted("blobs")) fields.push_back({"blobs", make_volume(n, blobs(n)), 0.5f});
  if (wanted("smooth")) fields.push_back({"smooth", make_volume(n, smooth(n)), 0.0f});
  if (wanted("empty"))
    fields.push_back({"empty", make_volume(n, std::vector<float>(static_cast<std::size_t>(n * n * n), -1.0f)), 0.0f});
  const auto cells = geotandem::tandem::cube_cells({n, n, n});
  for (const Field& f : fields) {
    for (int axis = 0; axis < 3; ++axis) {
      if (only_axis >= 0 && axis != only_axis) continue;
      const geotandem::tandem::McOptions options{f.iso, axis};
      const Run layers = best_of(repeats, [&] {
        geotandem::tandem::LayerExtractor x(f.volume, cells, options);
        geotandem::tandem::Layer layer;
        std::size_t triangles = 0;
        while (x.next(layer))
          triangles += layer.triangles.size();
        return triangles;
      });
      report(f.name, "layers", axis, n, layers);
    }
    if (only_axis > 0) continue;
    const Run welded = best_of(repeats, [&] {
      return geotandem::tandem::extract_surface(f.volume, cells, {f.iso, 0}).triangles.size();
    });
    report(f.name, "welded", 0, n, welded);
  }
  return 0;
}

int main(int argc, char** argv) {
  return geotandem::bench::guarded_main("bench_mc_throughput", [&] { return bench_main(argc, argv); });
}
