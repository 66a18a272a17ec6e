// The single-block tandem loop and the brute-force route (the seed's algorithms 2 and 4).
#include <algorithm>
#include <chrono>
#include <limits>
#include <string>

#include "geotandem/core/error.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "geotandem/tandem/tandem.hpp"

namespace geotandem::tandem {

void LayerStats::count(const SimplifyCounters& before, const SimplifyCounters& after) {
  collapses = after.collapses - before.collapses;
  rejected_shape = after.rejected_shape - before.rejected_shape;
  rejected_link = after.rejected_link - before.rejected_link;
  rejected_flip = after.rejected_flip - before.rejected_flip;
  components_dumped = after.components_dumped - before.components_dumped;
}

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

TandemStats run_loop(LayerSource& source, WorkingSurface& surface, const TandemOptions& options, bool brute) {
  const auto start = Clock::now();
  TandemStats stats;
  Layer layer;
  std::int64_t last_rank = 0;
  for (;;) {
    if (options.cancel) options.cancel->throw_if_cancelled();
    LayerStats s;
    const SimplifyCounters before = surface.counters();
    auto t = Clock::now();
    if (!source.next(layer)) break;
    s.seconds_extract = seconds_since(t);
    s.rank = layer.rank;
    s.input_triangles = layer.triangles.size();
    last_rank = layer.rank;

    t = Clock::now();
    surface.add_layer(layer); // extract(k); delay(k)
    s.seconds_insert = seconds_since(t);
    if (!brute) {
      t = Clock::now();
      surface.activate(static_cast<double>(layer.rank)); // activate(k)
      surface.simplify(options.cancel);                  // simplify(E0)
      s.seconds_simplify = seconds_since(t);
      if (options.dump) {
        t = Clock::now();
        surface.dump(); // dumping()
        s.seconds_dump = seconds_since(t);
      }
    }
    s.count(before, surface.counters());
    s.triangles_in_memory = surface.triangle_count();
    s.vertices_in_memory = surface.vertex_count();
    stats.peak_triangles = std::max<std::uint64_t>(stats.peak_triangles, s.triangles_in_memory);
    stats.layers.push_back(s);
    if (options.progress) options.progress->advance();
  }

  // activate(inf); simplify(E0); dumping()
  LayerStats& f = stats.final_pass;
  const SimplifyCounters before = surface.counters();
  f.rank = last_rank + 1;
  auto t = Clock::now();
  surface.activate(std::numeric_limits<double>::infinity());
  surface.simplify(options.cancel);
  f.seconds_simplify = seconds_since(t);
  t = Clock::now();
  surface.dump();
  f.seconds_dump = seconds_since(t);
  f.count(before, surface.counters());
  f.triangles_in_memory = surface.triangle_count();
  f.vertices_in_memory = surface.vertex_count();

  stats.counters = surface.counters();
  stats.remaining_triangles = surface.triangle_count();
  stats.seconds_total = seconds_since(start);
  return stats;
}

class McSource final : public LayerSource {
public:
  McSource(const volume::Volume& volume, const volume::Box& cells, const McOptions& options)
      : extractor_(volume, cells, options) {}
  bool next(Layer& layer) override { return extractor_.next(layer); }

private:
  LayerExtractor extractor_;
};

} // namespace

TandemStats run_tandem(LayerSource& source, WorkingSurface& surface, const TandemOptions& options) {
  return run_loop(source, surface, options, false);
}

TandemStats run_brute(LayerSource& source, WorkingSurface& surface, const TandemOptions& options) {
  return run_loop(source, surface, options, true);
}

std::unique_ptr<LayerSource> marching_cubes_source(const volume::Volume& volume, const volume::Box& cells,
                                                   const TandemOptions& options) {
  return std::make_unique<McSource>(volume, cells,
                                    McOptions{options.iso, options.axis, kMcSlabSamples, options.caps, options.below});
}

TandemStats extract_block(const volume::Volume& volume, const volume::Box& cells, const TandemOptions& options,
                          mesh::ComponentSink* sink, std::unique_ptr<WorkingSurface>* remaining, bool brute) {
  options.simplify.validate();
  const volume::Geometry& geometry = volume.geometry();
  const volume::Box cube = cube_cells(geometry.shape);
  auto source = marching_cubes_source(volume, cells, options);
  auto surface = std::make_unique<WorkingSurface>(geometry, Region::block(cube, cells), options.axis, options.simplify,
                                                  sink, options.observer);
  if (options.progress)
    options.progress->begin("tandem " + cells.to_string(), static_cast<std::uint64_t>(cells.size(options.axis)),
                            "layers");
  TandemStats stats = brute ? run_brute(*source, *surface, options) : run_tandem(*source, *surface, options);
  if (options.progress) options.progress->end();
  if (remaining) *remaining = std::move(surface);
  return stats;
}

} // namespace geotandem::tandem
