#pragma once
// The paths a run writes by itself (its store, state.json, the report, truth.json, the attribute
// cube, the input's copy), and the check that no export, report or store names one of them or
// the output directory itself: an export named report.html used to be replaced by the report when
// the run ended, and `output.store: .` made the store the output directory. Paths are compared
// once made absolute and weakly canonical, so "bodies.ply" and "/abs/out/bodies.ply" (or a path
// through a symbolic link) are one file.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "geotandem/workflow/recipe.hpp"
#include "yaml_reader.hpp"

namespace geotandem::workflow::detail {

// `path` absolute, `.` and `..` resolved, symbolic links of its existing part followed.
std::filesystem::path resolved(const std::filesystem::path& path);

// Which of the run's own files `target` (resolved) is or lies inside, as a phrase ("the run's
// report (report.html)"), or nothing. The output directory itself is the caller's to refuse (a
// file export may not be it; one file per component may go there). `target_is` names what `target` is, so that a file
// does not collide with itself ("report": the report's own path is not a collision).
std::optional<std::string> run_file_at(const OutputSpec& out, bool synthetic, const std::filesystem::path& target,
                                       const std::string& target_is);

// The problem with `output.store`: the output directory itself, or a directory holding it.
std::optional<std::string> store_problem(const OutputSpec& out);

// Refuses, at the recipe's line and column, an output section whose store is the output directory
// (or holds it), an export or a report that is one of the run's own files or the output
// directory, and two exports to one file. `m` reads the output section; `export_nodes` are the
// exports' nodes, in order.
void check_output_paths(MapReader& m, const Recipe& r, const std::vector<YAML::Node>& export_nodes);

} // namespace geotandem::workflow::detail
