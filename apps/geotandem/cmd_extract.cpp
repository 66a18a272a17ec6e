// geotandem extract CUBE --iso T --out STORE: the isosurface of a cube into a component store.

#include <chrono>
#include <iostream>

#include "command.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/store/local_sink.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/tandem/blocks.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/workflow/extract_step.hpp"

namespace geotandem::app {
namespace {

// --block-size N: the block tree of the seed's section 3.2, its leaves extracted one after the
// other and merged bottom-up in this process (tandem::extract_blocks), each partial surface passed
// through its wire form as the manager/worker runtime will ship it. The run is recorded in the
// store like workflow::extract_to_store records a one-block run.
int extract_in_blocks(const volume::Volume& cube, store::ComponentStore& store, const workflow::ExtractSettings& s,
                      Context& context, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  tandem::TandemOptions options;
  options.iso = s.iso;
  options.axis = s.axis;
  options.simplify.max_error = s.max_error;
  options.simplify.isotropy = s.isotropy;
  options.simplify.extended_time_lag = s.extended_time_lag;
  options.simplify.validate();
  options.dump = s.mode != workflow::ExtractMode::tandem;
  options.cancel = &context.cancel;
  options.progress = &progress;

  nlohmann::json parameters = s.parameters;
  parameters["iso"] = s.iso;
  parameters["max_error"] = s.max_error;
  parameters["isotropy"] = s.isotropy;
  parameters["axis"] = std::string(1, "ijk"[s.axis]);
  parameters["block_size"] = s.block_size;
  parameters["mode"] = workflow::to_string(s.mode);
  parameters["extended_time_lag"] = s.extended_time_lag;
  parameters["source"] = cube.source();
  const std::int64_t run = store.begin_run(parameters.dump());
  store::LocalSinkOptions sink_options;
  sink_options.run = run;
  store::LocalSink sink(store, sink_options);
  context.log.info("extracting in blocks of at most " + std::to_string(s.block_size) +
                   " cells per axis, one after the other, in this process");
  const tandem::BlocksStats b = tandem::extract_blocks(cube, tandem::cube_cells(cube.geometry().shape), s.block_size,
                                                       options, &sink, nullptr, s.mode == workflow::ExtractMode::brute);
  sink.close();

  const tandem::TandemStats& t = b.tandem;
  const std::uint64_t collapses = t.counters.collapses; // leaves, seams and the final pass
  std::uint64_t input = 0;
  double mc = 0, insert = 0, simplify = 0, dump = 0;
  std::vector<std::uint64_t> per_layer; // every leaf's layers in processing order
  for (const auto& layer : t.layers) {
    input += layer.input_triangles;
    per_layer.push_back(layer.triangles_in_memory);
    mc += layer.seconds_extract;
    insert += layer.seconds_insert;
    simplify += layer.seconds_simplify;
    dump += layer.seconds_dump;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::int64_t rss = workflow::peak_rss_kb();
  const nlohmann::json statistics = {{"components", sink.committed()},
                                     {"duplicates", sink.duplicates()},
                                     {"input_triangles", input},
                                     {"peak_triangles", t.peak_triangles},
                                     {"collapses", collapses},
                                     {"triangles_per_layer", per_layer},
                                     {"blocks",
                                      {{"leaves", b.leaves},
                                       {"merges", b.merges},
                                       {"seam_collapses", b.seam_collapses},
                                       {"components_at_merges", b.components_at_merges},
                                       {"peak_held_triangles", b.peak_held_triangles},
                                       {"wire_bytes", b.wire_bytes},
                                       {"largest_record", b.largest_record}}},
                                     {"seconds",
                                      {{"total", seconds},
                                       {"marching_cubes", mc},
                                       {"insert", insert},
                                       {"simplify", simplify},
                                       {"dump", dump},
                                       {"leaves", b.seconds_leaves},
                                       {"wire", b.seconds_wire},
                                       {"merge", b.seconds_merge}}},
                                     {"peak_rss_kb", rss}};
  store.end_run(run, statistics.dump());

  std::cout << "extracted " << sink.committed() << " components";
  if (sink.duplicates()) std::cout << " (" << sink.duplicates() << " already in the store)";
  std::cout << " from " << input << " marching-cubes triangles in " << seconds << " s; " << collapses
            << " collapses; at most " << t.peak_triangles << " triangles in one surface, " << b.peak_held_triangles
            << " held in all; peak memory " << rss / 1024 << " MiB\n"
            << "blocks: " << b.leaves << " leaves, " << b.merges << " merges (" << b.seam_collapses
            << " seam collapses), " << b.wire_bytes / 1024 << " KiB shipped; " << b.seconds_leaves << " s in leaves, "
            << b.seconds_merge << " s merging, " << b.seconds_wire << " s on the wire form\n"
            << "store: " << store.directory().string() << " (run " << run << ")\n";
  return 0;
}

} // namespace

void add_extract_command(CLI::App& app, Context& context, Runner& run) {
  struct Args {
    std::string cube, out, axis = "i", mode = "tandem-dump", nan = "error", variable;
    double iso = 0.0, max_error = 0.5, isotropy = 0.4;
    std::int64_t block_size = 0;
    bool no_extended_time_lag = false;
  };
  auto a = std::make_shared<Args>();
  auto* cmd =
      app.add_subcommand("extract", "Extract the isosurface value >= ISO of a cube with the extended tandem algorithm "
                                    "(marching cubes interleaved with edge-collapse simplification) into a component "
                                    "store. Finished components are written as they are found.");
  cmd->add_option("cube", a->cube, "the cube (any format 'geotandem info' reads)")->required();
  cmd->add_option("--iso", a->iso, "isovalue: samples >= ISO are inside a body")->required();
  cmd->add_option("--out", a->out, "the component store directory (created; resumed if it holds this cube)")
      ->required();
  cmd->add_option("--max-error", a->max_error, "E0: largest shape error a collapse may make, in voxels")
      ->capture_default_str();
  cmd->add_option("--isotropy", a->isotropy, "alpha in [0, 1]: weight of triangle shape against fidelity")
      ->capture_default_str();
  cmd->add_option("--axis", a->axis, "extraction axis: i (inline), j (crossline) or k (sample)")->capture_default_str();
  cmd->add_option("--block-size", a->block_size,
                  "leaf block edge of the block tree, in cells (at least 8; 0: the whole cube as one block). "
                  "The blocks are extracted one after the other and merged in this process")
      ->capture_default_str();
  cmd->add_option("--mode", a->mode, "tandem-dump, tandem (no early dumping) or brute (extract all, then simplify)")
      ->capture_default_str();
  cmd->add_flag("--no-extended-time-lag", a->no_extended_time_lag,
                "freeze only vertices on open block faces (for comparison; degrades seams)");
  cmd->add_option("--nan", a->nan, "NaN or infinite samples: error, or fill (treated as outside)")
      ->capture_default_str();
  cmd->add_option("--variable", a->variable, "the array to read from a multidimensional file with several");
  cmd->callback([a, &context, &run] {
    run = [a, &context] {
      volume::OpenOptions open;
      open.nan_policy = volume::parse_nan_policy(a->nan);
      open.variable = a->variable;
      workflow::ExtractSettings s;
      s.iso = static_cast<float>(a->iso);
      s.max_error = a->max_error;
      s.isotropy = a->isotropy;
      s.axis = workflow::parse_axis(a->axis);
      s.block_size = a->block_size;
      s.mode = workflow::parse_extract_mode(a->mode);
      s.extended_time_lag = !a->no_extended_time_lag;
      if (s.block_size != 0 && s.block_size < 8)
        throw InvalidArgument("--block-size must be 0 (one block) or at least 8 cells, got " +
                                  std::to_string(s.block_size),
                              {}, "blocks of 64 to 256 cells are typical");
      auto cube = volume::open_volume(a->cube, open);
      s.parameters = {{"command", "geotandem extract"}, {"cube", a->cube}};
      auto store = store::ComponentStore::open_or_create(a->out, cube->geometry(), {"geotandem extract", a->cube});
      auto progress = context.progress();
      if (s.block_size > 0) {
        if (!(store.geometry() == cube->geometry()))
          throw InvalidArgument("the store was made for another cube geometry", {a->out},
                                "extract into a new store directory");
        return extract_in_blocks(*cube, store, s, context, *progress);
      }
      auto r = workflow::extract_to_store(*cube, store, s, context.log, *progress, context.cancel);
      std::cout << "extracted " << r.components << " components";
      if (r.duplicates) std::cout << " (" << r.duplicates << " already in the store)";
      std::cout << " from " << r.input_triangles << " marching-cubes triangles in " << r.seconds << " s; "
                << r.collapses << " collapses; at most " << r.peak_triangles << " triangles in memory; peak memory "
                << r.peak_rss_kb / 1024 << " MiB\nstore: " << a->out << " (run " << r.run << ")\n";
      return 0;
    };
  });
}

} // namespace geotandem::app
