// geotandem extract CUBE --iso T --out STORE: the isosurface of a cube into a component store.
// Its options are the extraction's declared options (tandem::extraction_fields()): the same names,
// defaults, ranges, help and checks as in recipes, made into command-line options here.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <thread>

#include "command.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/tandem/extraction_options.hpp"
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

// The command line's spelling of an extraction option: --max-error for max_error; a boolean whose
// default is true is turned off with --no-NAME, one whose default is false turned on with --NAME.
std::string option_of(const ParamSpec& spec) {
  std::string name = spec.name;
  std::replace(name.begin(), name.end(), '_', '-');
  if (spec.type == ParamType::boolean) return spec.default_value == "true" ? "--no-" + name : "--" + name;
  return "--" + name;
}

std::string type_name_of(const ParamSpec& spec) {
  switch (spec.type) {
  case ParamType::real: return "NUMBER";
  case ParamType::integer: return "INT";
  case ParamType::choice: {
    std::string words;
    for (const auto& w : spec.choices)
      words += (words.empty() ? "" : "|") + w;
    return words;
  }
  case ParamType::boolean:
  case ParamType::text: break;
  }
  return "TEXT";
}

// The extraction's options (tandem::extraction_fields()) as this command's options: one per
// declared option, with its help, unit and default. Their texts go into `texts` by name.
void add_extraction_options(CLI::App& cmd, std::map<std::string, std::string>& texts) {
  for (const auto& field : tandem::extraction_fields()) {
    const ParamSpec& spec = field.spec;
    std::string help = spec.help + (spec.unit.empty() ? "" : " (" + spec.unit + ")");
    std::string& text = texts[spec.name];
    if (spec.type == ParamType::boolean) {
      const bool on_by_default = spec.default_value == "true";
      text = on_by_default ? "true" : "false";
      cmd.add_flag_function(
          option_of(spec), [&text, on_by_default](std::int64_t) { text = on_by_default ? "false" : "true"; },
          (on_by_default ? "off: " : "on: ") + help);
      continue;
    }
    auto* option = cmd.add_option(option_of(spec), text, help)->type_name(type_name_of(spec));
    if (spec.default_value) {
      text = *spec.default_value;
      option->capture_default_str();
    } else {
      option->required();
    }
  }
}

// The options' texts checked by their declarations, as one value; errors name the option.
tandem::ExtractionOptions extraction_options_of(const std::map<std::string, std::string>& texts) {
  workflow::ParamValues values;
  for (const auto& field : tandem::extraction_fields()) {
    const ParamSpec& spec = field.spec;
    try {
      values[spec.name] = parse_param(spec, texts.at(spec.name));
    } catch (const Error& e) {
      throw InvalidArgument(option_of(spec) + ": " + e.message(), {}, e.hint());
    }
  }
  try {
    return tandem::options_from_params(values);
  } catch (const Error& e) {
    // The checks across options name their parameter ("parameter 'block_size' ..."): name the option.
    std::string option;
    for (const auto& field : tandem::extraction_fields())
      if (e.message().find("'" + field.spec.name + "'") != std::string::npos) option = option_of(field.spec) + ": ";
    throw InvalidArgument(option + e.message(), {}, e.hint());
  }
}

} // namespace

void add_extract_command(CLI::App& app, Context& context, Runner& run) {
  struct Args {
    std::string cube, out, nan = "error", variable, crs;
    std::map<std::string, std::string> extraction; // by option name, as given or the default
    std::optional<std::size_t> workers;
    std::optional<double> no_data;
    bool fresh = false;
    volume::SegyOptions segy;
  };
  auto a = std::make_shared<Args>();
  auto* cmd =
      app.add_subcommand("extract", "Extract the isosurface value >= ISO (or value <= ISO with --side=below) of a "
                                    "cube with the extended tandem algorithm (marching cubes interleaved with "
                                    "edge-collapse simplification) into a component store. Finished components are "
                                    "written as they are found.");
  cmd->add_option("cube", a->cube, "the cube (any format 'geotandem info' reads)")->required();
  cmd->add_option("--out", a->out, "the component store directory (created; resumed if it holds this cube)")
      ->required();
  add_extraction_options(*cmd, a->extraction);
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
  add_crs_option(*cmd, a->crs);
  cmd->callback([a, &context, &run] {
    run = [a, &context] {
      volume::OpenOptions open;
      open.crs = crs_option(a->crs);
      open.nan_policy = volume::parse_nan_policy(a->nan);
      open.no_data = no_data_option(a->no_data);
      open.variable = a->variable;
      open.segy = a->segy;
      const tandem::ExtractionOptions options = extraction_options_of(a->extraction);
      // Filled missing samples (--nan fill) are outside on either side: the lowest float above,
      // the highest below.
      const bool below = options.side == tandem::Side::below;
      if (below) open.fill_value = std::numeric_limits<float>::max();
      workflow::ExecutionContext s;
      auto opening = context.progress(); // an irregular SEG-Y survey's pass over its headers
      open.progress = opening.get();
      auto cube = volume::open_volume(a->cube, open);
      workflow::require_cells(cube->geometry(), a->cube); // before the store is made
      for (const std::string& warning : volume::open_warnings(*cube))
        context.log.warning(warning);
      context.log.info("CRS: " + cube->geometry().crs.label());
      // One worker per core unless told otherwise (no more than there are blocks; one block is
      // extracted in this process); --workers 0 extracts in this process.
      s.workers = a->workers.value_or(workflow::default_worker_count(cube->geometry(), options.block_size));
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
            describe_cube_file(a->cube, a->nan, open.no_data, a->variable, a->segy, a->crs, cube->reopen_hint(), below);
        s.worker_command = worker_command(context);
      }
      s.record = {{"command", "geotandem extract"}, {"cube", a->cube}};
      // How the file is read decides the samples as much as its content: another array of a netCDF
      // file, other SEG-Y header bytes or other missing samples make another extraction.
      if (open.no_data) s.record["no_data"] = *open.no_data;
      if (!a->variable.empty()) { // as the file names it: "chaos" and "/chaos" are one array
        s.record["variable"] = a->variable;
        for (const auto& detail : cube->format_details())
          if (detail.key == "array") s.record["variable"] = detail.value;
      }
      if (!(a->segy == volume::SegyOptions{})) s.record["segy"] = volume::to_json(a->segy);
      auto progress = context.progress();
      auto r = workflow::extract_to_store(*cube, store, options, s, context.log, *progress, context.cancel);
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
      if (options.block_size > 0) {
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
