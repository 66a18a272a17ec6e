// GOCAD TSurf (ASCII): one object per component, from `GOCAD TSurf 1` to `END`, with its own
// 1-based vertex numbering, concatenated in one file. z is positive down (time or depth).

#include "export_writers.hpp"

namespace geotandem::store::detail {

void write_tsurf(SurfaceSource& source, std::ostream& out, const ExportOptions& options) {
  const auto& geometry = source.store().geometry();
  const bool time = geometry.z_unit == volume::SampleUnit::milliseconds;
  TextLines lines(out);
  for (std::size_t i = 0; i < source.size(); ++i) {
    const auto& row = source.row(i);
    const auto& surface = source.surface(i);
    lines << "GOCAD TSurf 1\nHEADER {\nname:" << options.name_prefix << std::uint64_t{row.key} << "\n}\n";
    lines << "GOCAD_ORIGINAL_COORDINATE_SYSTEM\nNAME Default\nAXIS_NAME \"X\" \"Y\" \"" << (time ? "TWT" : "Z")
          << "\"\nAXIS_UNIT \"m\" \"m\" \"" << (time ? "ms" : "m") << "\"\nZPOSITIVE " << (time ? "Time" : "Depth")
          << "\nEND_ORIGINAL_COORDINATE_SYSTEM\n";
    lines << "TFACE\n";
    std::uint64_t id = 1;
    for (const auto& p : surface.points) {
      lines << "VRTX " << id++ << ' ' << p[0] << ' ' << p[1] << ' ' << p[2];
      lines.end_line();
    }
    for (const auto& t : surface.triangles) {
      lines << "TRGL " << std::uint64_t{t[0]} + 1 << ' ' << std::uint64_t{t[1]} + 1 << ' ' << std::uint64_t{t[2]} + 1;
      lines.end_line();
    }
    lines << "END";
    lines.end_line();
  }
  lines.flush();
}

} // namespace geotandem::store::detail
