// geotandem store labels STORE --out PATH: the label cube of a store's bodies (issue 54, part 3),
// written afterwards from the field the store was extracted from, rebuilt from the store's last
// run: a recipe's chain (input and attributes), or the cube `geotandem extract` read.

#include <iostream>
#include <limits>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "command.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/workflow/chain.hpp"
#include "geotandem/workflow/label_cube.hpp"
#include "plugins_setup.hpp"

namespace geotandem::app {
namespace {

struct LabelArgs {
  std::string store, out, selection, cube, nan = "error", variable;
  std::optional<double> no_data;
  volume::SegyOptions segy;
  bool all = false, overwrite = false;
};

// The volume the run extracted from, kept alive with the registry whose plugins compute it, and
// the input file the label cube follows (its format family, its SEG-Y headers).
std::shared_ptr<const volume::Volume> field_of(const nlohmann::json& parameters, const LabelArgs& a, bool below,
                                               const volume::Crs& store_crs, Context& context,
                                               workflow::LabelLike& like) {
  const nlohmann::json chain = parameters.value("chain", nlohmann::json::object());
  if (a.cube.empty() && chain.is_object() && chain.contains("steps")) {
    struct Held {
      workflow::PluginRegistry registry;
      std::shared_ptr<const volume::Volume> volume;
    };
    auto held = std::make_shared<Held>(Held{make_plugin_registry(context.log), nullptr});
    const auto description = workflow::ChainDescription::from_json(chain);
    held->volume = workflow::open_chain(description, held->registry).result;
    like = workflow::label_like_of_input(description.input);
    return std::shared_ptr<const volume::Volume>(held, held->volume.get());
  }
  const std::string path = !a.cube.empty() ? a.cube : parameters.value("cube", "");
  if (path.empty())
    throw InvalidArgument("the store's run does not say which cube it read (an array extracted from Python?)",
                          {a.store}, "name the cube with --cube FILE");
  volume::OpenOptions open;
  open.nan_policy = volume::parse_nan_policy(a.nan);
  if (below) open.fill_value = std::numeric_limits<float>::max(); // filled samples stay outside
  open.no_data = no_data_option(a.no_data);
  if (!open.no_data && parameters.contains("no_data")) open.no_data = parameters["no_data"].get<float>();
  open.variable = !a.variable.empty() ? a.variable : parameters.value("variable", "");
  // The CRS the extraction used: the file's own, or the one `extract --crs` gave it (which the file
  // does not say). The label cube carries it.
  if (!store_crs.empty()) open.crs = store_crs;
  open.segy = a.segy;
  if (a.segy == volume::SegyOptions{} && parameters.contains("segy"))
    open.segy = volume::segy_options_from_json(parameters["segy"]);
  like.file = path;
  like.options = open;
  return volume::open_volume(path, open);
}

} // namespace

void add_store_labels(CLI::App* parent, Context& context, Runner& run) {
  auto a = std::make_shared<LabelArgs>();
  auto* cmd = parent->add_subcommand(
      "labels", "Write the label cube of the store's bodies: every sample's body ID (0 outside any body) on the "
                "extracted cube's grid, in the input's format family (a SEG-Y input: a copy of its file, every header "
                "kept; netCDF .nc, Zarr .zarr, raw .raw, GeoTIFF/ENVI .tif), with the table of IDs and store keys "
                "beside it (PATH.bodies.csv, PATH.bodies.json).");
  cmd->add_option("store", a->store, "the store directory")->required();
  cmd->add_option("--out", a->out, "the label cube to write")->required();
  cmd->add_option("--selection", a->selection,
                  "label the bodies of this named selection (default: the newest selection, as a recipe's last step "
                  "wrote it)");
  cmd->add_flag("--all", a->all, "label every component of the store, not a selection");
  cmd->add_option("--cube", a->cube,
                  "the cube the store was extracted from, when the store's run cannot reopen it (a moved file, an "
                  "array from Python); a recipe's run rebuilds its input and attributes itself");
  cmd->add_option("--nan", a->nan, "missing samples of --cube or the run's cube: error, or fill (outside)")
      ->capture_default_str();
  cmd->add_option("--no-data", a->no_data, "samples of this value are missing too")->type_name("VALUE");
  add_cube_reading_options(*cmd, a->variable, a->segy);
  cmd->add_flag("--overwrite", a->overwrite, "replace existing outputs");
  cmd->callback([a, &context, &run] {
    run = [a, &context] {
      auto store = store::ComponentStore::open(a->store);
      const auto runs = store.runs();
      if (runs.empty()) throw InvalidArgument("the store records no run", {a->store}, "extract into it first");
      const nlohmann::json parameters = nlohmann::json::parse(runs.back().parameters, nullptr, false);
      if (!parameters.is_object() || !parameters.contains("iso"))
        throw FormatError("the store's last run records no isovalue", {a->store});
      workflow::LabelSettings settings;
      settings.iso = parameters["iso"].get<float>();
      settings.below = parameters.value("side", "above") == "below";

      std::vector<std::uint64_t> keys;
      std::string selection = a->selection;
      if (!a->all && selection.empty()) {
        std::string newest;
        for (const auto& s : store.selections())
          if (s.created >= newest) {
            newest = s.created;
            selection = s.name;
          }
      }
      if (!a->all && !selection.empty())
        keys = store.load_selection(selection).keys;
      else
        for (const auto& row : store.query())
          keys.push_back(row.key);

      workflow::LabelLike like;
      auto field = field_of(parameters, *a, settings.below, store.geometry().crs, context, like);
      if (!(field->geometry() == store.geometry()))
        throw InvalidArgument("the cube's geometry is not the store's", {field->source()},
                              "label the cube the store was extracted from");
      const nlohmann::json description = {
          {"store", a->store}, {"selection", selection.empty() ? nlohmann::json(nullptr) : nlohmann::json(selection)}};
      auto progress = context.progress();
      const auto out = workflow::write_label_cube(field, settings, keys, like, a->out, a->overwrite, description,
                                                  "geotandem body labels (0 outside), table in .bodies.csv",
                                                  progress.get(), context.cancel);
      std::cout << "labelled " << out.bodies.size() << " bodies (" << keys.size() << " store keys"
                << (selection.empty() ? "" : " of selection '" + selection + "'") << ", side "
                << (settings.below ? "below" : "above") << " of " << settings.iso << ") in " << out.cube << "; table "
                << out.table << "; " << out.seconds_label << " s labelling, " << out.seconds_write << " s writing\n";
      return 0;
    };
  });
}

} // namespace geotandem::app
