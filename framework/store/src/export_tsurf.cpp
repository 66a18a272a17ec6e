// GOCAD TSurf (ASCII): one object per component, from `GOCAD TSurf 1` to `END`, with its own
// 1-based vertex numbering, concatenated in one file. z is positive down (time or depth). Each
// object's coordinate-system block names the store's CRS and the units of x, y and z; without a
// CRS it keeps GOCAD's "Default" name and a comment says "no CRS given".

#include <string>

#include "export_writers.hpp"

namespace geotandem::store::detail {

namespace {

// A GOCAD string: in double quotes, which it cannot hold itself.
std::string quoted(std::string text) {
  for (char& c : text)
    if (c == '"' || c == '\n' || c == '\r') c = '\'';
  return "\"" + text + "\"";
}

// GOCAD_ORIGINAL_COORDINATE_SYSTEM ... END_ORIGINAL_COORDINATE_SYSTEM, one per object.
std::string coordinate_system_block(const volume::Geometry& geometry) {
  const bool time = geometry.z_unit == volume::SampleUnit::milliseconds;
  const std::string xy = geometry.crs.empty() ? std::string("m") : geometry.crs.unit;
  std::string block = "GOCAD_ORIGINAL_COORDINATE_SYSTEM\n";
  if (geometry.crs.empty())
    block += std::string("# ") + volume::kNoCrs + "\nNAME Default\n";
  else
    block += "NAME " + quoted(geometry.crs.label()) + "\n";
  block += std::string("AXIS_NAME \"X\" \"Y\" \"") + (time ? "TWT" : "Z") + "\"\nAXIS_UNIT " + quoted(xy) + " " +
           quoted(xy) + " " + quoted(volume::to_string(geometry.z_unit)) + "\nZPOSITIVE " + (time ? "Time" : "Depth") +
           "\nEND_ORIGINAL_COORDINATE_SYSTEM\n";
  return block;
}

} // namespace

void write_tsurf(SurfaceSource& source, std::ostream& out, const ExportOptions& options) {
  const std::string block = coordinate_system_block(source.store().geometry());
  TextLines lines(out);
  for (std::size_t i = 0; i < source.size(); ++i) {
    const auto& row = source.row(i);
    const auto& surface = source.surface(i);
    lines << "GOCAD TSurf 1\nHEADER {\nname:" << options.name_prefix << std::uint64_t{row.key} << "\n}\n";
    lines << block;
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
