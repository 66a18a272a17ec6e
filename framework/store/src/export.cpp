// export_components: file naming, atomic placement, progress and cancellation. The formats live in
// export_<format>.cpp.

#include "geotandem/store/export.hpp"

#include <optional>

#include "export_writers.hpp"
#include "file_io.hpp"
#include "geotandem/core/atomic_file.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/core/output_path.hpp"
#include "geotandem/core/suggest.hpp"
#include "geotandem/mesh/caps.hpp"
#include "geotandem/store/check.hpp"

namespace geotandem::store {

using namespace detail;

namespace {

using Writer = void (*)(SurfaceSource&, std::ostream&, const ExportOptions&);
struct FormatRow {
  ExportFormatInfo info;
  Writer write;
};

const std::vector<FormatRow>& format_rows() {
  static const std::vector<FormatRow> rows = {
      {{ExportFormat::ply, "ply", "PLY: ParaView, MeshLab, CloudCompare, Blender"}, write_ply},
      {{ExportFormat::obj, "obj", "Wavefront OBJ"}, write_obj},
      {{ExportFormat::vtp, "vtp", "VTK XML PolyData: ParaView, with each body's key, volume and azimuth"}, write_vtp},
      {{ExportFormat::tsurf, "ts", "GOCAD TSurf: Petrel, SKUA-GOCAD, OpendTect"}, write_tsurf},
      // Not a stream: GDAL writes the file itself (write_gpkg, called by write_file).
      {{ExportFormat::gpkg, "gpkg",
        "GeoPackage: QGIS, ArcGIS, geopandas; layers 'footprints' (outlines seen from above) and 'centroids' with "
        "every measure of the index, in the store's CRS; with a selection its members only, otherwise a column "
        "in_NAME per selection of the store"},
       nullptr},
  };
  return rows;
}

const FormatRow& row_of(ExportFormat format) {
  for (const auto& r : format_rows())
    if (r.info.format == format) return r;
  throw InvalidArgument("unknown export format");
}

} // namespace

const std::vector<ExportFormatInfo>& export_formats() {
  static const std::vector<ExportFormatInfo> formats = [] {
    std::vector<ExportFormatInfo> out;
    for (const auto& r : format_rows())
      out.push_back(r.info);
    return out;
  }();
  return formats;
}

std::vector<std::string> export_format_names() {
  std::vector<std::string> names;
  for (const auto& f : export_formats())
    names.emplace_back(f.name);
  return names;
}

ExportFormat parse_export_format(const std::string& text) {
  for (const auto& f : export_formats())
    if (text == f.name) return f.format;
  if (text == "tsurf") return ExportFormat::tsurf;
  throw InvalidArgument("unknown export format '" + text + "'", {}, suggestion_hint(text, export_format_names()));
}

const char* file_extension(ExportFormat format) {
  return row_of(format).info.name;
}

namespace detail {

SurfaceSource::SurfaceSource(const ComponentStore& store, std::vector<const ComponentRow*> rows,
                             std::function<void()> on_first_read, std::uint64_t cache_budget, bool caps)
    : store_(store), rows_(std::move(rows)), on_first_read_(std::move(on_first_read)), seen_(rows_.size(), false),
      caps_(caps) {
  std::uint64_t total = 0;
  for (const auto* row : rows_)
    total += row->location.length;
  cache_all_ = total <= cache_budget;
  if (cache_all_) cache_.resize(rows_.size());
}

const mesh::SurfaceMesh& SurfaceSource::surface(std::size_t i) {
  if (cache_all_ && seen_[i]) return cache_[i];
  auto& target = cache_all_ ? cache_[i] : scratch_;
  target = store_.read(*rows_[i]);
  if (!caps_) target = mesh::without_world_caps(target, store_.geometry());
  if (!seen_[i]) {
    seen_[i] = true;
    if (on_first_read_) on_first_read_();
  }
  return target;
}

std::uint64_t SurfaceSource::vertex_count(std::size_t i) {
  return caps_ ? rows_[i]->location.vertex_count : surface(i).points.size();
}

std::uint64_t SurfaceSource::triangle_count(std::size_t i) {
  return caps_ ? rows_[i]->location.triangle_count : surface(i).triangles.size();
}

} // namespace detail

namespace {

void write_file(const ComponentStore& store, const std::vector<const ComponentRow*>& rows,
                const std::filesystem::path& path, const ExportOptions& options, const std::function<void()>& tick) {
  if (options.format == ExportFormat::gpkg) {
    write_gpkg(store, rows, path, options, tick);
    return;
  }
  // A unique temporary beside the target, renamed over it when whole: two exports to one path each
  // write their own, and the later rename wins with a complete file (AtomicFile removes the
  // temporary on an error or a cancel).
  AtomicFile file(path);
  std::ostream& out = file.stream();
  SurfaceSource source(store, rows, tick, 256ull << 20, options.caps);
  row_of(options.format).write(source, out, options);
  file.commit("the export file");
}

// The store directory that holds `path` (itself or an ancestor), if any.
std::optional<std::filesystem::path> enclosing_store(const std::filesystem::path& path) {
  std::error_code ec;
  auto p = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
  if (ec) return std::nullopt;
  for (auto dir = p; !dir.empty(); dir = dir.parent_path()) {
    if (ComponentStore::exists(dir)) return dir;
    if (dir == dir.root_path()) break;
  }
  return std::nullopt;
}

void refuse_existing(const std::filesystem::path& path, const ExportOptions& options) {
  std::error_code ec;
  if (!options.overwrite && std::filesystem::exists(std::filesystem::symlink_status(path, ec)))
    throw IoError("the export target already exists", {path.string()},
                  "pass --overwrite to replace it, or name another file");
  require_replaceable(path);
}

} // namespace

ExportSummary export_components(const ComponentStore& store, const std::vector<ComponentRow>& rows,
                                const std::filesystem::path& out, const ExportOptions& options, Progress& progress,
                                const CancelToken& cancel) {
  if (rows.empty())
    throw InvalidArgument("no component to export", {store.directory().string()},
                          "widen the filters; 'geotandem store ls' shows what the store holds");
  if (auto store_dir = enclosing_store(out))
    throw InvalidArgument("will not write an export inside a store directory (" + store_dir->string() + ")",
                          {out.string()}, "only the store writes there; export to a path outside it");
  if (options.format == ExportFormat::gpkg && options.per_component)
    throw InvalidArgument("a GeoPackage holds every component in one file: --per-component does not apply",
                          {out.string()}, "leave --per-component out");
  ExportSummary summary;
  std::vector<ComponentRow> intact;
  const std::vector<ComponentRow>* chosen = &rows;
  if (options.skip_damaged) {
    progress.begin("verifying", rows.size(), "components");
    std::uint64_t verified = 0;
    for (const auto& row : rows) {
      cancel.throw_if_cancelled();
      if (verify_component(store, row))
        summary.skipped.push_back(row.key);
      else
        intact.push_back(row);
      progress.update(++verified);
    }
    progress.end();
    if (intact.empty())
      throw FormatError("every selected component is damaged; nothing to export", {store.directory().string()},
                        "'geotandem store check' lists them; rerun the extraction to write them again");
    chosen = &intact;
  }
  const auto& rows_out = *chosen;
  for (const auto& row : rows_out) {
    summary.vertices += row.location.vertex_count;
    summary.triangles += row.location.triangle_count;
  }
  summary.components = rows_out.size();
  std::uint64_t done = 0;
  auto tick = [&] {
    cancel.throw_if_cancelled();
    progress.update(++done);
  };
  std::error_code ec;
  progress.begin("exporting", rows_out.size(), "components");
  if (options.per_component) {
    for (const auto& row : rows_out)
      refuse_existing(out / (options.name_prefix + std::to_string(row.key) + "." + file_extension(options.format)),
                      options);
    std::filesystem::create_directories(out, ec);
    if (ec || !std::filesystem::is_directory(out))
      throw IoError("cannot create the export directory" + (ec ? ": " + ec.message() : std::string()), {out.string()});
    for (const auto& row : rows_out) {
      auto path = out / (options.name_prefix + std::to_string(row.key) + "." + file_extension(options.format));
      write_file(store, {&row}, path, options, tick);
      summary.files.push_back(path);
    }
  } else {
    if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path(), ec);
    if (std::filesystem::is_directory(out))
      throw InvalidArgument("the export target is a directory", {out.string()},
                            "name a file, or export one file per component into the directory");
    refuse_existing(out, options);
    std::vector<const ComponentRow*> pointers;
    for (const auto& row : rows_out)
      pointers.push_back(&row);
    write_file(store, pointers, out, options, tick);
    summary.files.push_back(out);
  }
  progress.end();
  return summary;
}

} // namespace geotandem::store
