#include "output_paths.hpp"

#include <vector>

namespace fs = std::filesystem;

namespace geotandem::workflow::detail {
namespace {

// True when `inner` is `outer` or lies under it (both resolved).
bool within(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i)
    if (i == inner.end() || *i != *o) return false;
  return true;
}

} // namespace

fs::path resolved(const fs::path& path) {
  std::error_code ec;
  fs::path absolute = fs::absolute(path, ec);
  if (ec) absolute = path;
  fs::path canonical = fs::weakly_canonical(absolute, ec);
  if (ec) canonical = absolute.lexically_normal();
  // "a/b/" and "a/b" are one path.
  if (canonical.filename().empty() && canonical.has_parent_path()) canonical = canonical.parent_path();
  return canonical;
}

std::optional<std::string> run_file_at(const OutputSpec& out, bool synthetic, const fs::path& target,
                                       const std::string& target_is) {
  const fs::path dir = resolved(out.directory);
  struct Own {
    std::string name;
    fs::path path;
    bool directory;
    std::string label;
  };
  std::vector<Own> own = {{"store", resolved(dir / out.store), true, "the run's store (" + out.store + ")"},
                          {"state", dir / "state.json", false, "the run's state file (state.json)"},
                          {"report", resolved(dir / out.report), false, "the run's report (" + out.report + ")"},
                          {"copy", dir / "input-copy", true, "the input's copy (input-copy)"}};
  if (synthetic) own.push_back({"truth", dir / "truth.json", false, "the synthetic cube's ground truth (truth.json)"});
  if (!out.attribute_file.empty())
    own.push_back(
        {"attribute", resolved(dir / out.attribute_file), false, "the attribute cube (" + out.attribute_file + ")"});
  if (!out.labels_file.empty())
    own.push_back({"labels", resolved(dir / out.labels_file), false, "the label cube (" + out.labels_file + ")"});
  for (const Own& o : own) {
    if (o.name == target_is) continue;
    if (o.directory ? within(target, o.path) : target == o.path) return o.label;
  }
  return std::nullopt;
}

std::optional<std::string> store_problem(const OutputSpec& out) {
  const fs::path dir = resolved(out.directory);
  const fs::path store = resolved(dir / out.store);
  if (store == dir) return std::string("the store would be the output directory itself");
  if (within(dir, store)) return std::string("the store would hold the output directory");
  return std::nullopt;
}

void check_output_paths(MapReader& m, const Recipe& r, const std::vector<YAML::Node>& export_nodes) {
  const OutputSpec& out = r.output;
  if (auto problem = store_problem(out))
    throw error_at(m.source(), m.has("store") ? m.node("store") : m.map(),
                   "output.store '" + out.store + "': " + *problem, "name a directory inside it, such as 'store'");
  const fs::path dir = resolved(out.directory);
  const auto refuse = [&](const YAML::Node& node, const std::string& what, const std::string& path,
                          const std::string& problem, const std::string& hint) {
    throw error_at(m.source(), node, what + " writes " + path + ", " + problem, hint);
  };
  std::vector<fs::path> targets;
  for (std::size_t n = 0; n < out.exports.size(); ++n) {
    const ExportSpec& e = out.exports[n];
    const std::string what = "export " + std::to_string(n + 1);
    const fs::path target = resolved(dir / e.path);
    if (target == dir && !e.per_component)
      refuse(export_nodes.at(n), what, e.path, "the output directory itself", "name a file, such as bodies.ply");
    if (auto own = run_file_at(out, r.input.synthetic, target, ""))
      refuse(export_nodes.at(n), what, e.path, "which is " + *own + ": one would overwrite the other",
             "give the export another 'path'");
    for (std::size_t k = 0; k < targets.size(); ++k)
      if (targets[k] == target)
        refuse(export_nodes.at(n), what, e.path,
               "like an earlier export (export " + std::to_string(k + 1) + " writes " + out.exports[k].path +
                   ", the same file): the second would overwrite it",
               "give each export its own 'path'");
    targets.push_back(target);
  }
  const YAML::Node report_node = m.has("report") ? m.node("report") : m.map();
  const fs::path report = resolved(dir / out.report);
  if (report == dir) refuse(report_node, "the report", out.report, "the output directory itself", "name a file");
  if (auto own = run_file_at(out, r.input.synthetic, report, "report"))
    refuse(report_node, "the report", out.report, "which is " + *own + ": one would overwrite the other",
           "give the report another path, such as report.html");
  for (std::size_t k = 0; k < targets.size(); ++k)
    if (targets[k] == report)
      refuse(export_nodes.at(k), "export " + std::to_string(k + 1), out.exports[k].path,
             "the run's report (" + out.report + "): the report would replace it", "give the export another 'path'");
}

} // namespace geotandem::workflow::detail
