// geotandem extract CUBE --iso T --out STORE: the isosurface of a cube into a component store.
// Its options are the extract step's declared parameters: the same defaults, ranges and checks as
// in recipes (workflow::extract_params()).

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>
#include <string>
#include <thread>

#include "command.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/workflow/extract_step.hpp"

namespace geotandem::app {
namespace {

// Seconds as the progress lines give them: to a hundredth (a run's timings vary more than that).
std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", seconds);
  return text;
}

// " (3 damaged components written again: keys 17, 42, 99)": a repair rerun says what it repaired
// (the keys `store check` listed), not only "extracted 0 components".
std::string repaired_text(const workflow::ExtractResult& r) {
  if (r.repaired == 0) return {};
  std::string text = " (" + std::to_string(r.repaired) + " damaged component" + (r.repaired == 1 ? "" : "s") +
                     " written again: key" + (r.repaired == 1 ? " " : "s ");
  for (std::size_t i = 0; i < r.repaired_keys.size(); ++i)
    text += (i ? ", " : "") + std::to_string(r.repaired_keys[i]);
  if (r.repaired > r.repaired_keys.size())
    text += ", and " + std::to_string(r.repaired - r.repaired_keys.size()) + " more";
  return text + ")";
}

const workflow::ParamSpec& param(const std::string& name) {
  for (const auto& spec : workflow::extract_params())
    if (spec.name == name) return spec;
  throw InvalidArgument("the extract step declares no parameter '" + name + "'");
}

// The declared default of an extract parameter, as the command line's default text.
std::string default_of(const std::string& name) {
  return param(name).default_value.value_or("");
}

// The option's text validated by the extract step's declaration; errors name the option.
workflow::ParamValue value_of(const std::string& name, const std::string& option, const std::string& text) {
  try {
    return workflow::parse_param(param(name), text);
  } catch (const Error& e) {
    throw InvalidArgument(option + ": " + e.message(), {}, e.hint());
  }
}

} // namespace

void add_extract_command(CLI::App& app, Context& context, Runner& run) {
  struct Args {
    std::string cube, out, nan = "error", variable;
    std::string iso, side = default_of("side"), max_error = default_of("max_error"), isotropy = default_of("isotropy"),
                     axis = default_of("axis"), block_size = default_of("block_size"), mode = default_of("mode");
    bool no_extended_time_lag = false;
    std::optional<std::size_t> workers;
    std::optional<double> no_data;
    bool fresh = false;
    volume::SegyOptions segy;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand(
      "extract", "Extract the isosurface value >= ISO (or <= ISO) of a cube with the extended tandem algorithm "
                 "(marching cubes interleaved with edge-collapse simplification) into a component "
                 "store. Finished components are written as they are found.");
  cmd->add_option("cube", a->cube, "the cube (any format 'geotandem info' reads)")->required();
  cmd->add_option("--iso", a->iso, "isovalue: samples >= ISO (--side above) or <= ISO (--side below) are inside a body")
      ->required()
      ->type_name("NUMBER");
  cmd->add_option("--side", a->side,
                  "which side of ISO is inside a body: above (value >= ISO) or below (value <= ISO, e.g. low "
                  "coherence)")
      ->capture_default_str()
      ->type_name("above|below");
  cmd->add_option("--out", a->out, "the component store directory (created; resumed if it holds this cube)")
      ->required();
  cmd->add_option("--max-error", a->max_error,
                  "E0, in voxels: the simplified surface stays within E0 of the full-resolution one (guaranteed)")
      ->capture_default_str()
      ->type_name("NUMBER");
  cmd->add_option("--isotropy", a->isotropy, "alpha in [0, 1]: weight of triangle shape against fidelity")
      ->capture_default_str()
      ->type_name("NUMBER");
  cmd->add_option("--axis", a->axis, "extraction axis: i (inline), j (crossline) or k (sample)")
      ->capture_default_str()
      ->type_name("i|j|k");
  cmd->add_option("--block-size", a->block_size,
                  "leaf block edge of the block tree, in cells (at least " + std::to_string(workflow::min_block_size) +
                      "; 0: the whole cube as one block, in this process). The workers extract and merge the blocks in "
                      "parallel")
      ->capture_default_str()
      ->type_name("INT");
  cmd->add_option("--mode", a->mode, "tandem-dump, tandem (no early dumping) or brute (extract all, then simplify)")
      ->capture_default_str()
      ->type_name("MODE");
  cmd->add_flag("--no-extended-time-lag", a->no_extended_time_lag,
                "freeze only vertices on open block faces (for comparison; degrades seams)");
  cmd->add_option(
         "--nan", a->nan,
         "missing samples (NaN, infinite, or the file's declared no-data value): error, or fill (treated as outside)")
      ->capture_default_str();
  cmd->add_option("--no-data", a->no_data,
                  "samples of this value are missing too (SEG-Y and raw cubes cannot declare their null, often "
                  "-999.25); --nan says what becomes of them")
      ->type_name("VALUE");
  cmd->add_option("--workers", a->workers,
                  "local worker processes extracting and merging the blocks (manager/worker runtime); the default is "
                  "one per core, at most one per block (a cube of one block is extracted in this process); 0: "
                  "everything in this process, on one core")
      ->check(CLI::Range(0, 4096));
  // Start afresh instead of resuming (refused while another process writes the store).
  cmd->add_flag("--fresh", a->fresh, "replace the store in --out instead of resuming it");
  add_cube_reading_options(*cmd, a->variable, a->segy);
  cmd->callback([a, &context, &run] {
    run = [a, &context] {
      volume::OpenOptions open;
      open.nan_policy = volume::parse_nan_policy(a->nan);
      open.no_data = no_data_option(a->no_data);
      open.variable = a->variable;
      open.segy = a->segy;
      workflow::ParamValues values;
      values["iso"] = value_of("iso", "--iso", a->iso);
      values["side"] = value_of("side", "--side", a->side);
      values["max_error"] = value_of("max_error", "--max-error", a->max_error);
      values["isotropy"] = value_of("isotropy", "--isotropy", a->isotropy);
      values["axis"] = value_of("axis", "--axis", a->axis);
      values["block_size"] = value_of("block_size", "--block-size", a->block_size);
      values["mode"] = value_of("mode", "--mode", a->mode);
      values["extended_time_lag"] =
          value_of("extended_time_lag", "--no-extended-time-lag", a->no_extended_time_lag ? "false" : "true");
      workflow::ExtractSettings s;
      try {
        s = workflow::extract_settings(values);
      } catch (const Error& e) {
        throw InvalidArgument("--block-size: " + e.message(), {}, e.hint());
      }
      // Missing samples filled (--nan fill) must stay outside on the side below too.
      if (s.below) open.fill_value = std::numeric_limits<float>::max();
      auto opening = context.progress(); // an irregular SEG-Y survey's pass over its headers
      open.progress = opening.get();
      auto cube = volume::open_volume(a->cube, open);
      workflow::require_cells(cube->geometry(), a->cube); // before the store is made
      for (const std::string& warning : volume::open_warnings(*cube))
        context.log.warning(warning);
      // One worker per core unless told otherwise (no more than there are blocks; one block is
      // extracted in this process); --workers 0 extracts in this process.
      s.workers = a->workers.value_or(workflow::default_worker_count(cube->geometry(), s.block_size));
      if (a->fresh) store::ComponentStore::remove(a->out); // refuses while another process writes it
      // The store (and its writer lock) first: a second run into this store is refused before it
      // touches anything, the input's copy that the first run's workers read included.
      auto store = store::ComponentStore::open_or_create(a->out, cube->geometry(), {"geotandem extract", a->cube});
      std::string copy; // beside the store (STORE.input-copy), for a file that reads slowly by blocks
      {
        std::filesystem::path beside = std::filesystem::path(a->out).lexically_normal();
        if (beside.filename().empty()) beside = beside.parent_path(); // "store/"
        auto copying = context.progress();
        copy = workflow::copy_input_for_blocks(*cube, beside.string() + ".input-copy", context.log, *copying,
                                               context.cancel);
      }
      if (s.workers > 0) {
        s.volume_description =
            describe_cube_file(a->cube, a->nan, open.no_data, a->variable, a->segy, cube->reopen_hint());
        if (s.below) {
          auto d = nlohmann::json::parse(s.volume_description);
          d["fill"] = "highest";
          s.volume_description = d.dump();
        }
        s.worker_command = worker_command(context);
      }
      s.parameters = {{"command", "geotandem extract"}, {"cube", a->cube}};
      // How the file is read decides the samples as much as its content: another array of a netCDF
      // file, other SEG-Y header bytes or other missing samples make another extraction.
      if (open.no_data) s.parameters["no_data"] = *open.no_data;
      if (!a->variable.empty()) { // as the file names it: "chaos" and "/chaos" are one array
        s.parameters["variable"] = a->variable;
        for (const auto& detail : cube->format_details())
          if (detail.key == "array") s.parameters["variable"] = detail.value;
      }
      if (!(a->segy == volume::SegyOptions{}))
        s.parameters["segy"] = {{"inline_byte", a->segy.inline_byte}, {"crossline_byte", a->segy.crossline_byte}};
      auto progress = context.progress();
      auto r = workflow::extract_to_store(*cube, store, s, context.log, *progress, context.cancel);
      workflow::remove_input_copy(copy, context.log);
      std::cout << "extracted " << r.components << " components";
      if (r.duplicates) std::cout << " (" << r.duplicates << " already in the store)";
      std::cout << repaired_text(r);
      if (s.workers > 0) {
        const auto& st = r.statistics;
        std::cout << " in " << seconds_text(r.seconds) << " s with " << st["workers"] << " worker(s) (" << st["deaths"]
                  << " lost); tasks " << st["tasks"].dump() << "; "
                  << st["bytes"]["surfaces"].get<std::uint64_t>() / 1024 << " KiB of partial surfaces moved";
        if (st.value("skipped_leaves", 0) > 0)
          std::cout << "; resumed: " << st["skipped_leaves"] << " of " << st["leaves"]
                    << " blocks finished by an earlier run were not redone";
        std::cout << "\n";
        std::cout << "store: " << a->out << " (run " << r.run << ")\n";
        return 0;
      }
      std::cout << " from " << r.counters.input_triangles << " marching-cubes triangles in " << seconds_text(r.seconds)
                << " s; " << r.counters.collapses << " collapses (" << r.counters.rejected_distance
                << " candidates refused by the E0 distance bound); at most " << r.peak_triangles
                << " triangles in memory; peak memory " << r.peak_rss_kb / 1024 << " MiB\n";
      if (s.block_size > 0) {
        const auto& b = r.blocks;
        std::cout << "blocks: " << b["leaves"] << " leaves, " << b["merges"] << " merges (" << b["seam_collapses"]
                  << " seam collapses), " << b["wire_bytes"].get<std::uint64_t>() / 1024 << " KiB shipped; "
                  << seconds_text(b["seconds"]["leaves"].get<double>()) << " s in leaves, "
                  << seconds_text(b["seconds"]["merge"].get<double>()) << " s merging, "
                  << seconds_text(b["seconds"]["wire"].get<double>()) << " s on the wire form\n";
      }
      std::cout << "store: " << a->out << " (run " << r.run << ")\n";
      return 0;
    };
  });
}

} // namespace geotandem::app
