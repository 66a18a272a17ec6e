// geotandem extract CUBE --iso T --out STORE: the isosurface of a cube into a component store.

#include <iostream>
#include <optional>
#include <thread>

#include "command.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/workflow/extract_step.hpp"

namespace geotandem::app {
void add_extract_command(CLI::App& app, Context& context, Runner& run) {
  struct Args {
    std::string cube, out, axis = "i", mode = "tandem-dump", nan = "error", variable;
    double iso = 0.0, max_error = 0.5, isotropy = 0.4;
    std::int64_t block_size = 0;
    bool no_extended_time_lag = false;
    std::optional<std::size_t> workers;
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
  cmd->add_option("--workers", a->workers,
                  "local worker processes extracting and merging the blocks (manager/worker runtime); 0: in this "
                  "process. Default: one per core with --block-size, in this process for one block");
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
      s.workers = a->workers.value_or(s.block_size > 0 ? std::max(1u, std::thread::hardware_concurrency()) : 0u);
      if (s.workers > 0) {
        s.volume_description = describe_cube_file(a->cube, a->nan, a->variable);
        s.worker_command = {self_executable(), "worker"};
      }
      if (s.block_size != 0 && s.block_size < 8)
        throw InvalidArgument("--block-size must be 0 (one block) or at least 8 cells, got " +
                                  std::to_string(s.block_size),
                              {}, "blocks of 64 to 256 cells are typical");
      auto cube = volume::open_volume(a->cube, open);
      s.parameters = {{"command", "geotandem extract"}, {"cube", a->cube}};
      auto store = store::ComponentStore::open_or_create(a->out, cube->geometry(), {"geotandem extract", a->cube});
      auto progress = context.progress();
      auto r = workflow::extract_to_store(*cube, store, s, context.log, *progress, context.cancel);
      std::cout << "extracted " << r.components << " components";
      if (r.duplicates) std::cout << " (" << r.duplicates << " already in the store)";
      if (s.workers > 0) {
        const auto& st = r.statistics;
        std::cout << " in " << r.seconds << " s with " << st["workers"] << " worker(s) (" << st["deaths"]
                  << " lost); tasks " << st["tasks"].dump() << "; "
                  << st["bytes"]["surfaces"].get<std::uint64_t>() / 1024 << " KiB of partial surfaces moved\n";
        std::cout << "store: " << a->out << " (run " << r.run << ")\n";
        return 0;
      }
      std::cout << " from " << r.input_triangles << " marching-cubes triangles in " << r.seconds << " s; "
                << r.collapses << " collapses; at most " << r.peak_triangles << " triangles in memory; peak memory "
                << r.peak_rss_kb / 1024 << " MiB\n";
      if (s.block_size > 0) {
        const auto& b = r.blocks;
        std::cout << "blocks: " << b["leaves"] << " leaves, " << b["merges"] << " merges (" << b["seam_collapses"]
                  << " seam collapses), " << b["wire_bytes"].get<std::uint64_t>() / 1024 << " KiB shipped; "
                  << b["seconds"]["leaves"] << " s in leaves, " << b["seconds"]["merge"] << " s merging, "
                  << b["seconds"]["wire"] << " s on the wire form\n";
      }
      std::cout << "store: " << a->out << " (run " << r.run << ")\n";
      return 0;
    };
  });
}

} // namespace geotandem::app
