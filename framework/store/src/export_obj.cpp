// Wavefront OBJ: one object per component (`o <prefix><key>`), 1-based vertex numbers across the
// whole file.

#include "export_writers.hpp"

namespace geotandem::store::detail {

void write_obj(SurfaceSource& source, std::ostream& out, const ExportOptions& options) {
  TextLines lines(out);
  lines << "# geotandem component store export, world coordinates: " << std::uint64_t{source.size()} << " components\n";
  std::uint64_t base = 1;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const auto& row = source.row(i);
    const auto& surface = source.surface(i);
    lines << "o " << options.name_prefix << std::uint64_t{row.key} << "\n# key " << std::uint64_t{row.key} << " volume "
          << row.stats.volume << " azimuth " << row.stats.azimuth;
    lines.end_line();
    for (const auto& p : surface.points) {
      lines << "v " << p[0] << ' ' << p[1] << ' ' << p[2];
      lines.end_line();
    }
    for (const auto& t : surface.triangles) {
      lines << "f " << base + t[0] << ' ' << base + t[1] << ' ' << base + t[2];
      lines.end_line();
    }
    base += surface.points.size();
  }
  lines.flush();
}

} // namespace geotandem::store::detail
