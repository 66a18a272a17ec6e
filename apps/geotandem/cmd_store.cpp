// geotandem store ls|show|export|runs|selections|check STORE: look into a component store without
// reading its raw data (ls, show, runs), export what a filter selects, verify every record.

#include <charconv>
#include <cstdio>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/store/check.hpp"
#include "geotandem/store/export.hpp"
#include "geotandem/store/store.hpp"
#include "store_filters.hpp"

namespace geotandem::app {
namespace {

std::uint64_t parse_key(const std::string& text) {
  std::uint64_t key = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), key);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty())
    throw InvalidArgument("bad component key '" + text + "'", {},
                          "a key is a non-negative integer, as 'store ls' lists");
  return key;
}

nlohmann::json json_text_or_string(const std::string& text) {
  auto j = nlohmann::json::parse(text, nullptr, false);
  return j.is_discarded() ? nlohmann::json(text) : j;
}

nlohmann::json row_json(const store::ComponentRow& r) {
  const auto& s = r.stats;
  char checksum[24];
  std::snprintf(checksum, sizeof checksum, "%016llx", static_cast<unsigned long long>(r.location.checksum));
  return {{"key", r.key},
          {"vertex_count", r.location.vertex_count},
          {"triangle_count", r.location.triangle_count},
          {"volume", s.volume},
          {"samples", r.samples_counted ? nlohmann::json(s.samples) : nlohmann::json(nullptr)},
          {"area", s.area},
          {"centroid", s.centroid},
          {"box_min", s.box_min},
          {"box_max", s.box_max},
          {"obb", {{"center", s.obb_center}, {"axes", s.obb_axes}, {"half_extents", s.obb_half_extents}}},
          {"azimuth", s.azimuth},
          {"dip", s.dip},
          {"elongation", s.elongation},
          {"closed", s.closed},
          {"cut_by_border", s.cut_by_border},
          {"cut_faces", mesh::cut_faces_text(s.cut_faces)},
          {"cap_area", s.cap_area},
          {"run", r.run ? nlohmann::json(*r.run) : nlohmann::json(nullptr)},
          {"shard", r.location.shard},
          {"offset", r.location.offset},
          {"length", r.location.length},
          {"checksum", checksum}};
}

std::string format_number(double value, const char* format = "%.6g") {
  char text[48];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

void print_table(const std::vector<store::ComponentRow>& rows, std::uint64_t total, const std::string& unit) {
  auto& o = std::cout;
  char line[256];
  std::snprintf(line, sizeof line, "%20s %14s %12s %8s %6s %10s %10s  %s\n", "key", ("volume " + unit).c_str(),
                "samples", "azimuth", "dip", "vertices", "triangles", "surface");
  o << line;
  for (const auto& r : rows) {
    const auto& s = r.stats;
    const std::string faces = mesh::cut_faces_text(s.cut_faces);
    const std::string kind = s.cut_by_border ? "cut " + (faces.empty() ? std::string("by border") : faces)
                             : s.closed      ? "closed"
                                             : "open";
    // Rows from before volumes in samples: "-".
    const std::string samples = r.samples_counted ? std::to_string(s.samples) : "-";
    std::snprintf(line, sizeof line, "%20llu %14s %12s %8.2f %6.2f %10llu %10llu  %s\n",
                  static_cast<unsigned long long>(r.key), format_number(s.volume).c_str(), samples.c_str(), s.azimuth,
                  s.dip, static_cast<unsigned long long>(r.location.vertex_count),
                  static_cast<unsigned long long>(r.location.triangle_count), kind.c_str());
    o << line;
  }
  o << "# " << rows.size() << " of " << total << " components\n";
}

// "(m2.ms)", "(m3)", "(ft3)": the volume unit as the table has always shown it.
std::string volume_unit_text(const volume::Geometry& g) {
  std::string text;
  for (char c : volume::volume_unit(g))
    if (c != '^') text += c == '*' ? '.' : c;
  return "(" + text + ")";
}

void print_show(const store::ComponentRow& r, const volume::Geometry& g) {
  auto& o = std::cout;
  const auto& s = r.stats;
  auto triple = [](const std::array<double, 3>& v) {
    return format_number(v[0], "%.3f") + ", " + format_number(v[1], "%.3f") + ", " + format_number(v[2], "%.3f");
  };
  const std::string z = volume::to_string(g.z_unit);
  o << "key:            " << r.key << "\n";
  o << "vertices:       " << r.location.vertex_count << "\n";
  o << "triangles:      " << r.location.triangle_count << "\n";
  o << "surface:        " << (s.closed ? "closed" : "open");
  if (s.cut_by_border) {
    o << ", cut by the cube border";
    if (s.cut_faces != 0)
      o << " (faces " << mesh::cut_faces_text(s.cut_faces) << "; caps " << format_number(s.cap_area) << " of the area)";
  }
  o << "\n";
  o << "volume:         " << format_number(s.volume) << " " << volume_unit_text(g) << "\n";
  o << "samples:        " << (r.samples_counted ? std::to_string(s.samples) : std::string("- (not counted)"))
    << " (samples enclosed: the volume in voxels)\n";
  o << "area:           " << format_number(s.area) << "\n";
  const std::string xy = g.crs.empty() ? std::string("m") : g.crs.unit;
  o << "centroid:       " << triple(s.centroid) << "  (x " << xy << ", y " << xy << ", z " << z << ")\n";
  o << "box min:        " << triple(s.box_min) << "\n";
  o << "box max:        " << triple(s.box_max) << "\n";
  o << "obb center:     " << triple(s.obb_center) << "\n";
  for (int a = 0; a < 3; ++a)
    o << "obb axis " << a << ":     " << triple(s.obb_axes[static_cast<std::size_t>(a)]) << "  half extent "
      << format_number(s.obb_half_extents[static_cast<std::size_t>(a)]) << "\n";
  o << "azimuth:        " << format_number(s.azimuth, "%.2f") << " deg from north (axial)\n";
  o << "dip:            " << format_number(s.dip, "%.2f") << " deg\n";
  o << "elongation:     " << format_number(s.elongation, "%.3f") << "\n";
  o << "crs:            " << g.crs.label() << "\n";
  o << "run:            " << (r.run ? std::to_string(*r.run) : std::string("-")) << "\n";
  o << "record:         shards/" << r.location.shard << ".gts offset " << r.location.offset << ", " << r.location.length
    << " bytes, xxh64 " << row_json(r)["checksum"].get<std::string>() << "\n";
}

struct LsArgs {
  std::string store;
  Filters filters;
  bool json = false;
};

struct ShowArgs {
  std::string store, key;
  bool json = false;
};

struct ExportArgs {
  std::string store, format, out;
  Filters filters;
  bool per_component = false, float32 = false, overwrite = false, skip_damaged = false, no_caps = false;
};

struct ListArgs {
  std::string store;
  bool json = false;
};

void add_ls(CLI::App* parent, Runner& run) {
  auto args = std::make_shared<LsArgs>();
  auto* cmd = parent->add_subcommand("ls", "List components from the index (no raw data is read).");
  cmd->add_option("store", args->store, "the store directory")->required();
  args->filters.add_to(cmd);
  cmd->add_flag("--json", args->json, "print every index field as JSON");
  cmd->callback([args, &run] {
    run = [args] {
      auto s = store::ComponentStore::open(args->store);
      auto q = args->filters.query();
      auto rows = s.query(q);
      if (args->json) {
        nlohmann::json list = nlohmann::json::array();
        for (const auto& r : rows)
          list.push_back(row_json(r));
        std::cout << list.dump(2) << "\n";
      } else {
        print_table(rows, s.size(), volume_unit_text(s.geometry()));
      }
      return 0;
    };
  });
}

void add_show(CLI::App* parent, Runner& run) {
  auto args = std::make_shared<ShowArgs>();
  auto* cmd = parent->add_subcommand("show", "Show every index field of one component.");
  cmd->add_option("store", args->store, "the store directory")->required();
  cmd->add_option("key", args->key, "the component key")->required();
  cmd->add_flag("--json", args->json, "print JSON");
  cmd->callback([args, &run] {
    run = [args] {
      auto s = store::ComponentStore::open(args->store);
      auto key = parse_key(args->key);
      auto row = s.find(key);
      if (!row)
        throw InvalidArgument("no component with key " + std::to_string(key) + " in the store", {args->store},
                              "list the keys with 'geotandem store ls'");
      if (args->json)
        std::cout << row_json(*row).dump(2) << "\n";
      else
        print_show(*row, s.geometry());
      return 0;
    };
  });
}

void add_export(CLI::App* parent, Context& context, Runner& run) {
  auto args = std::make_shared<ExportArgs>();
  auto* cmd = parent->add_subcommand("export", "Export the components a filter selects (all by default).");
  cmd->add_option("store", args->store, "the store directory")->required();
  std::string formats;
  for (const auto& f : store::export_formats())
    formats += std::string(formats.empty() ? "" : "; ") + f.name + " (" + f.summary + ")";
  cmd->add_option("--format", args->format, formats)->required();
  cmd->add_option("--out", args->out, "the output file, or directory with --per-component")->required();
  cmd->add_flag("--per-component", args->per_component, "one file per component, named geobody_<key>.<ext>");
  cmd->add_flag("--float32", args->float32, "PLY: float32 vertices instead of float64");
  cmd->add_flag("--overwrite", args->overwrite, "replace output files that already exist");
  cmd->add_flag("--skip-damaged", args->skip_damaged,
                "verify every record first and export the intact ones, listing the damaged keys");
  cmd->add_flag("--no-caps", args->no_caps,
                "leave out the caps that close bodies cut by the cube's border (export their open surface)");
  args->filters.add_to(cmd);
  cmd->callback([args, &context, &run] {
    run = [args, &context] {
      store::ExportOptions options;
      options.format = store::parse_export_format(args->format);
      options.per_component = args->per_component;
      options.ply_float32 = args->float32;
      options.overwrite = args->overwrite;
      options.skip_damaged = args->skip_damaged;
      options.caps = !args->no_caps;
      options.selection = args->filters.selection;
      auto s = store::ComponentStore::open(args->store);
      auto rows = s.query(args->filters.query());
      auto progress = context.progress();
      auto summary = store::export_components(s, rows, args->out, options, *progress, context.cancel);
      std::cout << "exported " << summary.components << " components (" << summary.vertices << " vertices, "
                << summary.triangles << " triangles) to " << summary.files.size() << " file"
                << (summary.files.size() == 1 ? "" : "s") << (args->per_component ? " in " : ": ") << args->out << "\n";
      if (!summary.skipped.empty()) {
        std::cout << "skipped " << summary.skipped.size() << " damaged component"
                  << (summary.skipped.size() == 1 ? "" : "s") << ":";
        for (auto key : summary.skipped)
          std::cout << " " << key;
        std::cout << "\n";
        context.log.warning("skipped " + std::to_string(summary.skipped.size()) +
                            " damaged components; rerun the extraction into the store to write them again");
      }
      return 0;
    };
  });
}

// A listing of the store's index (`store runs`, `store selections`): its rows as JSON with --json,
// else `print_row` for each, or `empty` when there is none.
void add_listing(CLI::App* parent, Runner& run, const std::string& name, const std::string& help,
                 const std::string& empty, std::function<nlohmann::json(const store::ComponentStore&)> rows,
                 std::function<void(const nlohmann::json&)> print_row) {
  auto args = std::make_shared<ListArgs>();
  auto* cmd = parent->add_subcommand(name, help);
  cmd->add_option("store", args->store, "the store directory")->required();
  cmd->add_flag("--json", args->json, "print JSON");
  cmd->callback([args, &run, rows, print_row, empty] {
    run = [args, rows, print_row, empty] {
      const nlohmann::json list = rows(store::ComponentStore::open(args->store));
      if (args->json) {
        std::cout << list.dump(2) << "\n";
        return 0;
      }
      if (list.empty()) std::cout << empty << "\n";
      for (const auto& row : list)
        print_row(row);
      return 0;
    };
  });
}

void add_runs(CLI::App* parent, Runner& run) {
  add_listing(
      parent, run, "runs", "List the runs that wrote the store, with their statistics.", "no runs recorded",
      [](const store::ComponentStore& s) {
        nlohmann::json list = nlohmann::json::array();
        for (const auto& r : s.runs())
          list.push_back({{"id", r.id},
                          {"started", r.started},
                          {"ended", r.ended.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.ended)},
                          {"components", r.component_count},
                          {"parameters", json_text_or_string(r.parameters)},
                          {"statistics", json_text_or_string(r.statistics)}});
        return list;
      },
      [](const nlohmann::json& r) {
        std::cout << "run " << r["id"] << ": started " << r["started"].get<std::string>() << ", "
                  << (r["ended"].is_null() ? std::string("not ended (running, or killed)")
                                           : "ended " + r["ended"].get<std::string>())
                  << ", " << r["components"] << " components\n";
        std::cout << "  parameters: " << r["parameters"].dump() << "\n";
        std::cout << "  statistics: " << r["statistics"].dump() << "\n";
      });
}

void add_selections(CLI::App* parent, Runner& run) {
  add_listing(
      parent, run, "selections", "List the named selections (e.g. written by component steps).", "no selections",
      [](const store::ComponentStore& s) {
        nlohmann::json list = nlohmann::json::array();
        for (const auto& sel : s.selections())
          list.push_back({{"name", sel.name},
                          {"size", sel.size},
                          {"created", sel.created},
                          {"parameters", json_text_or_string(sel.parameters)}});
        return list;
      },
      [](const nlohmann::json& sel) {
        std::cout << sel["name"].get<std::string>() << ": " << sel["size"] << " components, created "
                  << sel["created"].get<std::string>() << ", " << sel["parameters"].dump() << "\n";
      });
}

void add_check(CLI::App* parent, Context& context, Runner& run) {
  auto args = std::make_shared<ListArgs>();
  auto* cmd = parent->add_subcommand(
      "check", "Read back and verify every component record (checksums); list the damaged ones by key. "
               "Exit status 4 when any is damaged. Rerunning the same extraction into the store writes them again; "
               "'store export --skip-damaged' exports the others.");
  cmd->alias("verify");
  cmd->add_option("store", args->store, "the store directory")->required();
  cmd->add_flag("--json", args->json, "print JSON");
  cmd->callback([args, &context, &run] {
    run = [args, &context] {
      auto s = store::ComponentStore::open(args->store);
      auto progress = context.progress();
      auto report = store::check_store(s, *progress, context.cancel);
      if (args->json) {
        nlohmann::json damaged = nlohmann::json::array();
        for (const auto& d : report.damaged)
          damaged.push_back({{"key", d.key},
                             {"shard", d.location.shard},
                             {"offset", d.location.offset},
                             {"length", d.location.length},
                             {"problem", d.problem}});
        std::cout << nlohmann::json{{"checked", report.checked},
                                    {"damaged", damaged},
                                    {"rows_without_checksum", report.rows_without_checksum},
                                    {"seconds", report.seconds}}
                         .dump(2)
                  << "\n";
      } else {
        for (const auto& d : report.damaged)
          std::cout << "damaged: key " << d.key << ": " << d.problem << "\n";
        // Rows from before row checksums: their records are verified, their measures cannot be.
        if (!report.index_has_row_checksums)
          std::cout << "note: no row checksums in this store (written before index rows were checksummed): "
                    << "the records are verified, the index's measures are not\n";
        else if (report.rows_without_checksum > 0)
          std::cout << "note: " << report.rows_without_checksum << " of " << report.checked
                    << " rows have no row checksum (written before row checksums): their measures are not verified\n";
        std::cout << "checked " << report.checked << " components in " << format_number(report.seconds, "%.3f")
                  << " s: ";
        if (report.damaged.empty())
          std::cout << "all intact\n";
        else
          std::cout << report.damaged.size() << " damaged (rerun the same extraction into this store to write them "
                    << "again, or export the others with 'store export --skip-damaged')\n";
      }
      return report.damaged.empty() ? 0 : 4;
    };
  });
}

} // namespace

void add_store_command(CLI::App& app, Context& context, Runner& run) {
  auto* cmd = app.add_subcommand("store", "Query and export a component store (index + raw data shards).");
  cmd->require_subcommand(1);
  add_ls(cmd, run);
  add_show(cmd, run);
  add_export(cmd, context, run);
  add_runs(cmd, run);
  add_selections(cmd, run);
  add_check(cmd, context, run);
  add_store_labels(cmd, context, run);
}

} // namespace geotandem::app
