// Parameter specs of the built-in steps that are not attribute plugins. They drive validation,
// `geotandem plugins`, and docs/recipe-schema.md.

#include <map>

#include "geotandem/core/error.hpp"
#include "geotandem/workflow/recipe.hpp"

namespace geotandem::workflow {
namespace {

ParamSpec real(std::string name, std::optional<std::string> def, std::string help, std::optional<double> lo,
               std::optional<double> hi = {}) {
  return ParamSpec{std::move(name), ParamType::real, std::move(def), std::move(help), lo, hi, {}};
}
ParamSpec integer(std::string name, std::string def, std::string help, double lo, double hi) {
  return ParamSpec{std::move(name), ParamType::integer, std::move(def), std::move(help), lo, hi, {}};
}
ParamSpec boolean(std::string name, std::string def, std::string help) {
  return ParamSpec{std::move(name), ParamType::boolean, std::move(def), std::move(help), {}, {}, {}};
}
ParamSpec choice(std::string name, std::string def, std::string help, std::vector<std::string> choices) {
  return ParamSpec{std::move(name), ParamType::choice, std::move(def), std::move(help), {}, {}, std::move(choices)};
}
ParamSpec text(std::string name, std::string def, std::string help) {
  return ParamSpec{std::move(name), ParamType::text, std::move(def), std::move(help), {}, {}, {}};
}

const std::map<std::string, std::vector<ParamSpec>>& table() {
  static const std::map<std::string, std::vector<ParamSpec>> specs = {
      {"extract",
       {real("iso", std::nullopt, "isovalue: samples >= iso are inside a body", std::nullopt),
        real("max_error", "0.5", "E0, the largest shape error a collapse may make, in voxels", 1e-6, 100.0),
        real("isotropy", "0.4", "alpha, weight of triangle shape against surface fidelity", 0.0, 1.0),
        choice("axis", "i", "extraction axis: i (inline), j (crossline) or k (sample)", {"i", "j", "k"}),
        integer("block_size", "128", "leaf block edge in cells for the block tree (0: the whole cube as one block)", 0,
                4096),
        choice("mode", "tandem-dump",
               "tandem-dump (default), tandem (no early dumping), brute (extract, then simplify)",
               {"tandem-dump", "tandem", "brute"}),
        boolean("extended_time_lag", "true", "delay collapses near open block faces (the seed's section 3.2)")}},
      {"remove_bubbles",
       {real("min_volume", "0", "keep components of at least this volume, in world units (m^3 or m^2*ms)", 0.0),
        real("min_volume_fraction", "0", "keep components of at least this fraction of the largest volume", 0.0, 1.0),
        real("min_volume_percentile", "0", "keep components at or above this percentile of volumes", 0.0, 100.0),
        integer("min_triangles", "0", "keep components of at least this many triangles", 0, 1e12),
        boolean("closed_only", "false", "drop components cut by the cube's border"),
        text("selection", "kept", "name of the selection this step writes")}},
      {"sort_by_azimuth",
       {integer("bins", "18", "number of azimuth bins over 0-180 degrees", 1, 180),
        real("azimuth_min", "0", "keep azimuths from this value (degrees, axial; may wrap past 180)", 0.0, 180.0),
        real("azimuth_max", "180", "keep azimuths up to this value (degrees)", 0.0, 180.0),
        text("selection", "sorted", "name of the selection this step writes")}},
  };
  return specs;
}

} // namespace

const std::vector<ParamSpec>& builtin_step_params(const std::string& name) {
  auto it = table().find(name);
  if (it == table().end()) throw InvalidArgument("no built-in step named '" + name + "'");
  return it->second;
}

std::vector<std::string> builtin_step_names() {
  std::vector<std::string> names;
  for (const auto& [name, specs] : table())
    names.push_back(name);
  return names;
}

} // namespace geotandem::workflow
