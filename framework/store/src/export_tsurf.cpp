// GOCAD TSurf (ASCII): one object per component, from `GOCAD TSurf 1` to `END`, with its own
// 1-based vertex numbering, concatenated in one file. z is positive down (time or depth).

#include "export_writers.hpp"

namespace geotandem::store::detail {

void write_tsurf(SurfaceSource& source, std::ostream& out, const ExportOptions& options) {
  const auto& geometry = source.store().geometry();
  const bool time = geometry.z_unit == volume::SampleUnit::milliseconds;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const auto& row = source.row(i);
    const auto& surface = source.surface(i);
    out << "GOCAD TSurf 1\nHEADER {\nname:" << options.name_prefix << row.key << "\n}\n";
    out << "GOCAD_ORIGINAL_COORDINATE_SYSTEM\nNAME Default\nAXIS_NAME \"X\" \"Y\" \"" << (time ? "TWT" : "Z")
        << "\"\nAXIS_UNIT \"m\" \"m\" \"" << (time ? "ms" : "m") << "\"\nZPOSITIVE " << (time ? "Time" : "Depth")
        << "\nEND_ORIGINAL_COORDINATE_SYSTEM\n";
    out << "TFACE\n";
    std::uint64_t id = 1;
    for (const auto& p : surface.points) {
      out << "VRTX ";
      put_number(out, id++);
      for (double c : p) {
        out << ' ';
        put_number(out, c);
      }
      out << '\n';
    }
    for (const auto& t : surface.triangles) {
      out << "TRGL";
      for (auto v : t) {
        out << ' ';
        put_number(out, std::uint64_t{v} + 1);
      }
      out << '\n';
    }
    out << "END\n";
  }
}

} // namespace geotandem::store::detail
