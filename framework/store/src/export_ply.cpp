// Binary little-endian PLY: every vertex of every component, then every face with a `body`
// property (the component's position in the export; comments map it to the key).

#include <cstring>
#include <string>
#include <vector>

#include "export_writers.hpp"

namespace geotandem::store::detail {

void write_ply(SurfaceSource& source, std::ostream& out, const ExportOptions& options) {
  std::uint64_t vertices = 0, faces = 0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    vertices += source.vertex_count(i);
    faces += source.triangle_count(i);
  }
  const char* type = options.ply_float32 ? "float" : "double";
  out << "ply\nformat binary_little_endian 1.0\ncomment geotandem component store export, world coordinates\n";
  // The CRS on one comment line (PLY comments end at the line): its label, or "no CRS given".
  const volume::Geometry& geometry = source.store().geometry();
  std::string crs = geometry.crs.label();
  for (char& c : crs)
    if (c == '\n' || c == '\r') c = ' ';
  out << "comment crs " << crs << "\ncomment units x " << (geometry.crs.empty() ? "m" : geometry.crs.unit) << " y "
      << (geometry.crs.empty() ? "m" : geometry.crs.unit) << " z " << volume::to_string(geometry.z_unit) << "\n";
  for (std::size_t i = 0; i < source.size(); ++i) {
    const auto& row = source.row(i);
    out << "comment body " << i << " key " << row.key << " volume ";
    put_number(out, row.stats.volume);
    out << " azimuth ";
    put_number(out, row.stats.azimuth);
    out << "\n";
  }
  out << "element vertex " << vertices << "\nproperty " << type << " x\nproperty " << type << " y\nproperty " << type
      << " z\nelement face " << faces << "\nproperty list uchar int vertex_indices\nproperty uint body\nend_header\n";

  std::vector<char> buffer;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const auto& surface = source.surface(i);
    if (options.ply_float32) {
      buffer.resize(surface.points.size() * 12);
      char* p = buffer.data();
      for (const auto& point : surface.points)
        for (double c : point) {
          float f = static_cast<float>(c);
          std::memcpy(p, &f, 4);
          p += 4;
        }
      out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    } else {
      out.write(reinterpret_cast<const char*>(surface.points.data()),
                static_cast<std::streamsize>(surface.points.size() * sizeof(mesh::Point)));
    }
  }
  std::uint64_t base = 0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const auto& surface = source.surface(i);
    buffer.resize(surface.triangles.size() * 17);
    char* p = buffer.data();
    const auto body = static_cast<std::uint32_t>(i);
    for (const auto& triangle : surface.triangles) {
      *p++ = 3;
      for (auto v : triangle) {
        auto index = static_cast<std::int32_t>(base + v);
        std::memcpy(p, &index, 4);
        p += 4;
      }
      std::memcpy(p, &body, 4);
      p += 4;
    }
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    base += surface.points.size();
  }
}

} // namespace geotandem::store::detail
