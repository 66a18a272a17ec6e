// export_components: file naming, atomic placement, progress and cancellation. The formats live in
// export_<format>.cpp.

#include "geotandem/store/export.hpp"

#include <cerrno>
#include <fstream>

#include "export_writers.hpp"
#include "file_io.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::store {

using namespace detail;

ExportFormat parse_export_format(const std::string& text) {
  if (text == "ply") return ExportFormat::ply;
  if (text == "obj") return ExportFormat::obj;
  if (text == "vtp") return ExportFormat::vtp;
  if (text == "ts" || text == "tsurf") return ExportFormat::tsurf;
  throw InvalidArgument("unknown export format '" + text + "'", {}, "use ply, obj, vtp or ts (GOCAD TSurf)");
}

const char* file_extension(ExportFormat format) {
  switch (format) {
  case ExportFormat::ply: return "ply";
  case ExportFormat::obj: return "obj";
  case ExportFormat::vtp: return "vtp";
  case ExportFormat::tsurf: return "ts";
  }
  return "dat";
}

namespace detail {

SurfaceSource::SurfaceSource(const ComponentStore& store, std::vector<const ComponentRow*> rows,
                             std::function<void()> on_first_read, std::uint64_t cache_budget)
    : store_(store), rows_(std::move(rows)), on_first_read_(std::move(on_first_read)), seen_(rows_.size(), false) {
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
  if (!seen_[i]) {
    seen_[i] = true;
    if (on_first_read_) on_first_read_();
  }
  return target;
}

} // namespace detail

namespace {

void write_file(const ComponentStore& store, const std::vector<const ComponentRow*>& rows,
                const std::filesystem::path& path, const ExportOptions& options, const std::function<void()>& tick) {
  auto part = path;
  part += ".part";
  {
    std::ofstream out(part, std::ios::binary | std::ios::trunc);
    if (!out) throw IoError("cannot create export file: " + errno_text(errno), {part.string()});
    SurfaceSource source(store, rows, tick);
    try {
      switch (options.format) {
      case ExportFormat::ply: write_ply(source, out, options); break;
      case ExportFormat::obj: write_obj(source, out, options); break;
      case ExportFormat::vtp: write_vtp(source, out, options); break;
      case ExportFormat::tsurf: write_tsurf(source, out, options); break;
      }
      out.flush();
      if (!out) throw IoError("cannot write export file", {part.string()}, "is the disk full?");
    } catch (...) {
      out.close();
      std::error_code ec;
      std::filesystem::remove(part, ec);
      throw;
    }
  }
  std::error_code ec;
  std::filesystem::rename(part, path, ec);
  if (ec) throw IoError("cannot move the export into place: " + ec.message(), {path.string()});
}

} // namespace

ExportSummary export_components(const ComponentStore& store, const std::vector<ComponentRow>& rows,
                                const std::filesystem::path& out, const ExportOptions& options, Progress& progress,
                                const CancelToken& cancel) {
  if (rows.empty())
    throw InvalidArgument("no component to export", {store.directory().string()},
                          "widen the filters; 'geotandem store ls' shows what the store holds");
  ExportSummary summary;
  for (const auto& row : rows) {
    summary.vertices += row.location.vertex_count;
    summary.triangles += row.location.triangle_count;
  }
  summary.components = rows.size();
  std::uint64_t done = 0;
  auto tick = [&] {
    cancel.throw_if_cancelled();
    progress.update(++done);
  };
  std::error_code ec;
  progress.begin("exporting", rows.size(), "components");
  if (options.per_component) {
    std::filesystem::create_directories(out, ec);
    if (ec || !std::filesystem::is_directory(out))
      throw IoError("cannot create the export directory" + (ec ? ": " + ec.message() : std::string()), {out.string()});
    for (const auto& row : rows) {
      auto path = out / (options.name_prefix + std::to_string(row.key) + "." + file_extension(options.format));
      write_file(store, {&row}, path, options, tick);
      summary.files.push_back(path);
    }
  } else {
    if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path(), ec);
    if (std::filesystem::is_directory(out))
      throw InvalidArgument("the export target is a directory", {out.string()},
                            "name a file, or export one file per component into the directory");
    std::vector<const ComponentRow*> pointers;
    for (const auto& row : rows)
      pointers.push_back(&row);
    write_file(store, pointers, out, options, tick);
    summary.files.push_back(out);
  }
  progress.end();
  return summary;
}

} // namespace geotandem::store
