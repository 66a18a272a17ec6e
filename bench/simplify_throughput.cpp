// Extraction plus simplification throughput on one core: the tandem with dumping against brute
// force (extract everything, then simplify once with the same cost), on generated fields; "seed" is
// the tandem without the E0 guarantee (SimplifyOptions::guarantee_distance off), for its cost.
//
//   bench_simplify_throughput [n=256] [fields=blobs,smooth,seismic] [E0=0.5] [modes=tandem,brute,seed]
//                             [compaction_min_dead=16384]
//
// Fields: blobs (Gaussian blobs and uniform noise, iso 0.5), smooth (a few dozen large blobs, iso
// 0.35), seismic (the attribute of workflows/quickstart.yaml, read from the source tree, on its
// synthetic cube at n^3, at the recipe's isovalue; today chaos planarity x the envelope normalised
// by its 99th percentile on the seismic cube of seed 1 and SNR 4, iso 0.2: issue 12's "quickstart's
// seismic attribute"). The seismic field is computed once, before the clock starts: the figures are
// the collapse loop's, not the attributes'.
//
// Per run: input triangles (marching cubes), triangles and components out, CPU seconds of the
// thread (the figure per core, robust when other processes share the machine) split into
// extraction (marching cubes), insertion, simplification and dumping; input triangles per CPU
// second, collapses per second of simplification, and the most triangles held at a layer boundary.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <sys/resource.h>

#include "bench_args.hpp"
#include "geotandem/builtin/register.hpp"
#include "geotandem/mesh/component.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "geotandem/tandem/tandem.hpp"
#include "geotandem/volume/volume.hpp"
#include "geotandem/workflow/chain.hpp"
#include "geotandem/workflow/recipe.hpp"

using namespace geotandem;

namespace {

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

// Adds a Gaussian bump of height `height` and width `sigma` at c, over its 3-sigma box.
void add_blob(std::vector<float>& f, std::int64_t n, const double c[3], double sigma, double height) {
  const auto r = static_cast<std::int64_t>(std::ceil(3.0 * sigma));
  std::int64_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::max<std::int64_t>(0, static_cast<std::int64_t>(c[a]) - r);
    hi[a] = std::min<std::int64_t>(n, static_cast<std::int64_t>(c[a]) + r + 1);
  }
  const double inv = 1.0 / (2.0 * sigma * sigma);
  for (std::int64_t i = lo[0]; i < hi[0]; ++i)
    for (std::int64_t j = lo[1]; j < hi[1]; ++j) {
      const double dij = (static_cast<double>(i) - c[0]) * (static_cast<double>(i) - c[0]) +
                         (static_cast<double>(j) - c[1]) * (static_cast<double>(j) - c[1]);
      for (std::int64_t k = lo[2]; k < hi[2]; ++k) {
        const double dk = static_cast<double>(k) - c[2];
        f[static_cast<std::size_t>((i * n + j) * n + k)] +=
            static_cast<float>(height * std::exp(-(dij + dk * dk) * inv));
      }
    }
}

// The quickstart recipe's attribute on an n^3 cube, and the isovalue its extract step uses. The
// recipe is read from the source tree when the bench runs (only its shape is changed), so the field
// is always the one the quickstart computes.
struct Field {
  std::vector<float> values;
  float iso = 0.0f;
};
Field quickstart_field(std::int64_t n) {
  workflow::PluginRegistry registry;
  builtin::register_builtins(registry);
  const std::string edge = std::to_string(n);
  const workflow::Recipe recipe = workflow::load_recipe(
      GEOTANDEM_QUICKSTART_RECIPE, registry, {"input.synthetic.shape=[" + edge + "," + edge + "," + edge + "]"});
  // describe_chain refuses a recipe without an extract step; its parameters are validated text.
  const workflow::ChainDescription chain = workflow::describe_chain(recipe, registry);
  Field field;
  field.iso = std::stof(chain.extract_step().params.at("iso"));
  const auto volume = workflow::open_chain_volume(chain, registry);
  field.values = volume->read(volume::Box::of_shape({n, n, n}));
  return field;
}

// Noisy: many small blobs and uniform noise (many small components, bubbles, thin necks).
// Smooth: a few dozen large blobs, no noise (large smooth bodies). Seismic: above.
std::vector<float> make_field(const std::string& kind, std::int64_t n) {
  std::vector<float> f(static_cast<std::size_t>(n * n * n), 0.0f);
  std::mt19937 rng(kind == "blobs" ? 2024u : 7u);
  std::uniform_real_distribution<double> where(0.0, static_cast<double>(n));
  const double scale = static_cast<double>(n) / 256.0;
  if (kind == "blobs") {
    std::uniform_real_distribution<double> width(1.8, 5.0);
    const int count = static_cast<int>(1800.0 * scale * scale * scale) + 1;
    for (int b = 0; b < count; ++b) {
      const double c[3] = {where(rng), where(rng), where(rng)};
      add_blob(f, n, c, width(rng), 1.0);
    }
    std::uniform_real_distribution<float> noise(-0.1f, 0.1f);
    for (float& x : f)
      x += noise(rng);
  } else {
    std::uniform_real_distribution<double> width(10.0 * scale, 24.0 * scale);
    for (int b = 0; b < 40; ++b) {
      const double c[3] = {where(rng), where(rng), where(rng)};
      add_blob(f, n, c, width(rng), 1.0);
    }
  }
  return f;
}

class CountingSink final : public mesh::ComponentSink {
public:
  void commit(const mesh::Component& c) override {
    ++components;
    triangles += c.surface.triangle_count();
  }
  std::uint64_t components = 0;
  std::uint64_t triangles = 0;
};

} // namespace

int bench_main(int argc, char** argv) {
  const geotandem::bench::Args args(argc, argv,
                                    "bench_simplify_throughput [n=256] [fields=blobs,smooth,seismic] [E0=0.5] "
                                    "[modes=tandem,brute,seed] [compaction_min_dead=16384]");
  const std::int64_t n = args.integer(1, 256, 2);
  const std::vector<std::string> fields = args.words(2, "blobs,smooth", {"blobs", "smooth", "seismic"});
  const double e0 = args.real(3, 0.5, 0.0);
  const std::vector<std::string> modes = args.words(4, "tandem,brute", {"tandem", "brute", "seed"});
  const auto min_dead = static_cast<std::size_t>(args.integer(5, 16384, 0));
  std::printf("cube %lld^3, E0 %.2f voxel, alpha 0.4, extraction along axis 0, one thread\n", static_cast<long long>(n),
              e0);
  for (const std::string& kind : fields) {
    volume::Geometry g;
    g.shape = {n, n, n};
    Field field;
    if (kind == "seismic")
      field = quickstart_field(n);
    else
      field = {make_field(kind, n), kind == "blobs" ? 0.5f : 0.35f};
    volume::MemoryVolume volume(g, std::move(field.values), "bench " + kind);
    const float iso = field.iso;
    const volume::Box cells = tandem::cube_cells(g.shape);

    // Marching cubes alone, for the share of extraction.
    tandem::LayerExtractor extractor(volume, cells, {iso, 0});
    tandem::Layer layer;
    std::uint64_t mc_triangles = 0;
    double t0 = cpu_seconds();
    while (extractor.next(layer))
      mc_triangles += layer.triangles.size();
    const double mc_cpu = cpu_seconds() - t0;
    std::printf("\nfield %s (iso %.2f): %llu triangles, marching cubes alone %.2f s CPU (%.2f M triangles/s)\n",
                kind.c_str(), static_cast<double>(iso), static_cast<unsigned long long>(mc_triangles), mc_cpu,
                1e-6 * static_cast<double>(mc_triangles) / mc_cpu);
    std::printf("%-7s %9s %8s %7s %7s %7s %7s %7s %7s %8s %9s %9s %8s\n", "mode", "in-tris", "out-tris", "comps",
                "cpu-s", "mc-s", "ins-s", "simp-s", "dump-s", "Mtri/s", "kcoll/s", "peak-tris", "rss-MB");
    for (const std::string& mode : modes) {
      tandem::TandemOptions options;
      options.iso = iso;
      options.axis = 0;
      options.simplify.max_error = e0;
      options.simplify.compaction_min_dead = min_dead;
      // "seed": the tandem without the E0 guarantee (eps_0 <= E0 only), for its cost.
      options.simplify.guarantee_distance = mode != "seed";
      CountingSink sink;
      t0 = cpu_seconds();
      const tandem::TandemStats s = tandem::extract_block(volume, cells, options, &sink, nullptr, mode == "brute");
      const double cpu = cpu_seconds() - t0;
      double mc = 0, ins = 0, simp = s.final_pass.seconds_simplify, dump = s.final_pass.seconds_dump;
      for (const tandem::LayerStats& l : s.layers) {
        mc += l.seconds_extract;
        ins += l.seconds_insert;
        simp += l.seconds_simplify;
        dump += l.seconds_dump;
      }
      // Wall-clock phase times are scaled to the run's CPU time (they differ only by preemption).
      const double wall = mc + ins + simp + dump;
      const double k = wall > 0 ? cpu / wall : 1.0;
      std::printf("%-7s %9llu %8llu %7llu %7.2f %7.2f %7.2f %7.2f %7.2f %8.2f %9.0f %9llu %8.0f\n", mode.c_str(),
                  static_cast<unsigned long long>(s.counters.input_triangles),
                  static_cast<unsigned long long>(sink.triangles), static_cast<unsigned long long>(sink.components),
                  cpu, k * mc, k * ins, k * simp, k * dump,
                  1e-6 * static_cast<double>(s.counters.input_triangles) / cpu,
                  1e-3 * static_cast<double>(s.counters.collapses) / (k * simp),
                  static_cast<unsigned long long>(s.peak_triangles), peak_rss_mb());
      const tandem::SimplifyCounters& c = s.counters;
      std::printf("        collapses %llu, cost evaluations %llu, refused: shape %llu, link %llu, flip %llu, "
                  "distance bound %llu (retried %llu), minimiser distrusted %llu, compactions %llu\n",
                  static_cast<unsigned long long>(c.collapses), static_cast<unsigned long long>(c.evaluations),
                  static_cast<unsigned long long>(c.rejected_shape), static_cast<unsigned long long>(c.rejected_link),
                  static_cast<unsigned long long>(c.rejected_flip),
                  static_cast<unsigned long long>(c.rejected_distance), static_cast<unsigned long long>(c.retried),
                  static_cast<unsigned long long>(c.distrusted),
                  static_cast<unsigned long long>(c.garbage_collections));
    }
  }
  return 0;
}

int main(int argc, char** argv) {
  return geotandem::bench::guarded_main("bench_simplify_throughput", [&] { return bench_main(argc, argv); });
}
