// VTK XML PolyData, ASCII arrays (plain, well-formed XML that any XML parser and ParaView read).
// One piece holds every component; per-body key, volume and azimuth are cell data (for colouring
// and thresholding in ParaView) and field data (one tuple per body).

#include "export_writers.hpp"

namespace geotandem::store::detail {
namespace {

template <class Value>
void field_array(std::ostream& out, SurfaceSource& source, const char* type, const char* name,
                 Value (*get)(const ComponentRow&)) {
  out << "      <DataArray type=\"" << type << "\" Name=\"" << name << "\" NumberOfTuples=\"" << source.size()
      << "\" format=\"ascii\">\n       ";
  for (std::size_t i = 0; i < source.size(); ++i) {
    out << ' ';
    put_number(out, get(source.row(i)));
  }
  out << "\n      </DataArray>\n";
}

template <class Value>
void cell_array(std::ostream& out, SurfaceSource& source, const char* type, const char* name,
                Value (*get)(const ComponentRow&, std::size_t)) {
  out << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < source.size(); ++i) {
    const auto& row = source.row(i);
    Value value = get(row, i);
    const std::uint64_t triangles = source.triangle_count(i);
    for (std::uint64_t t = 0; t < triangles; ++t) {
      out << (t % 16 == 0 ? "\n         " : " ");
      put_number(out, value);
    }
  }
  out << "\n        </DataArray>\n";
}

std::uint64_t key_of(const ComponentRow& row) {
  return row.key;
}
double volume_of(const ComponentRow& row) {
  return row.stats.volume;
}
double azimuth_of(const ComponentRow& row) {
  return row.stats.azimuth;
}

} // namespace

void write_vtp(SurfaceSource& source, std::ostream& out, const ExportOptions&) {
  std::uint64_t points = 0, polys = 0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    points += source.vertex_count(i);
    polys += source.triangle_count(i);
  }
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
         "  <PolyData>\n    <FieldData>\n";
  field_array<std::uint64_t>(out, source, "UInt64", "key", key_of);
  field_array<double>(out, source, "Float64", "volume", volume_of);
  field_array<double>(out, source, "Float64", "azimuth", azimuth_of);
  out << "    </FieldData>\n    <Piece NumberOfPoints=\"" << points
      << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"" << polys << "\">\n";
  out << "      <CellData Scalars=\"volume\">\n";
  cell_array<std::uint64_t>(out, source, "UInt64", "key", [](const ComponentRow& r, std::size_t) { return r.key; });
  cell_array<double>(out, source, "Float64", "volume",
                     [](const ComponentRow& r, std::size_t) { return r.stats.volume; });
  cell_array<double>(out, source, "Float64", "azimuth",
                     [](const ComponentRow& r, std::size_t) { return r.stats.azimuth; });
  cell_array<std::uint64_t>(out, source, "UInt32", "body",
                            [](const ComponentRow&, std::size_t i) { return std::uint64_t{i}; });
  out << "      </CellData>\n";

  out << "      <Points>\n        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" "
         "format=\"ascii\">\n";
  for (std::size_t i = 0; i < source.size(); ++i)
    for (const auto& p : source.surface(i).points) {
      out << "         ";
      put_number(out, p[0]);
      out << ' ';
      put_number(out, p[1]);
      out << ' ';
      put_number(out, p[2]);
      out << '\n';
    }
  out << "        </DataArray>\n      </Points>\n";

  out << "      <Polys>\n        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  std::uint64_t base = 0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const auto& surface = source.surface(i);
    for (const auto& t : surface.triangles) {
      out << "         ";
      put_number(out, std::uint64_t{base + t[0]});
      out << ' ';
      put_number(out, std::uint64_t{base + t[1]});
      out << ' ';
      put_number(out, std::uint64_t{base + t[2]});
      out << '\n';
    }
    base += surface.points.size();
  }
  out << "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::uint64_t c = 1; c <= polys; ++c) {
    out << (c % 16 == 1 ? "\n         " : " ");
    put_number(out, std::uint64_t{3 * c});
  }
  out << "\n        </DataArray>\n      </Polys>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
}

} // namespace geotandem::store::detail
