// Wavefront OBJ: one object per component (`o <prefix><key>`), 1-based vertex numbers across the
// whole file.

#include "export_writers.hpp"

namespace geotandem::store::detail {

void write_obj(SurfaceSource& source, std::ostream& out, const ExportOptions& options) {
  out << "# geotandem component store export, world coordinates: " << source.size() << " components\n";
  std::uint64_t base = 1;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const auto& row = source.row(i);
    const auto& surface = source.surface(i);
    out << "o " << options.name_prefix << row.key << "\n# key " << row.key << " volume ";
    put_number(out, row.stats.volume);
    out << " azimuth ";
    put_number(out, row.stats.azimuth);
    out << "\n";
    for (const auto& p : surface.points) {
      out << "v ";
      put_number(out, p[0]);
      out << ' ';
      put_number(out, p[1]);
      out << ' ';
      put_number(out, p[2]);
      out << '\n';
    }
    for (const auto& t : surface.triangles) {
      out << "f ";
      put_number(out, std::uint64_t{base + t[0]});
      out << ' ';
      put_number(out, std::uint64_t{base + t[1]});
      out << ' ';
      put_number(out, std::uint64_t{base + t[2]});
      out << '\n';
    }
    base += surface.points.size();
  }
}

} // namespace geotandem::store::detail
