// VTK XML PolyData 1.0 with every DataArray in VTK's inline binary encoding (format="binary"): the
// array's byte count as a UInt64 (header_type), then its values, both little-endian and base64
// encoded together as one block on one line, uncompressed; vtkXMLWriter lays out an uncompressed
// array the same way. The file stays well-formed XML that any XML parser reads, and ParaView opens
// it. One piece holds every component; per-body key, volume and azimuth are cell data (for
// colouring and thresholding in ParaView) and field data (one tuple per body). The field data also
// holds the CRS as string arrays of one tuple (crs: its label or "no CRS given", crs_wkt, and
// crs_units: the units of x, y and z), binary as VTK writes strings: the characters ended by 0.
//
// The byte count comes first, so it is computed from the index's counts before any surface is
// read; the surfaces then stream one at a time, and an array whose values do not match its count
// fails the export instead of writing a header that lies.

#include <algorithm>
#include <array>
#include <bit>
#include <string>
#include <type_traits>

#include "base64.hpp"
#include "export_writers.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::store::detail {
namespace {

static_assert(std::endian::native == std::endian::little,
              "VTP arrays are written from memory as little-endian; a big-endian port must byte-swap them");
static_assert(sizeof(mesh::Point) == 3 * sizeof(double), "points are written as packed triples of doubles");

// The VTK name of each value type the arrays use.
template <class Value> constexpr const char* vtk_type_name() {
  if constexpr (std::is_same_v<Value, double>) return "Float64";
  if constexpr (std::is_same_v<Value, std::uint64_t>) return "UInt64";
  if constexpr (std::is_same_v<Value, std::int64_t>) return "Int64";
  if constexpr (std::is_same_v<Value, std::uint32_t>) return "UInt32";
  if constexpr (std::is_same_v<Value, std::int32_t>) return "Int32";
  static_assert(std::is_same_v<Value, double> || std::is_same_v<Value, std::uint64_t> ||
                    std::is_same_v<Value, std::int64_t> || std::is_same_v<Value, std::uint32_t> ||
                    std::is_same_v<Value, std::int32_t>,
                "a value type without a VTK name");
}

// One <DataArray> of `count` values of type Value: the constructor writes the opening tag and the
// byte count, put* stream the values, close() ends the element.
template <class Value> class BinaryArray {
public:
  // `attributes` is inserted into the opening tag as it is (e.g. NumberOfComponents="3").
  BinaryArray(std::ostream& out, const char* indent, const char* name, std::uint64_t count,
              const std::string& attributes = {})
      : out_(out), indent_(indent), name_(name), count_(count), encoder_(out) {
    out_ << indent_ << "<DataArray type=\"" << vtk_type_name<Value>() << "\" Name=\"" << name_ << '"' << attributes
         << " format=\"binary\">\n"
         << indent_ << "  ";
    const std::uint64_t bytes = count_ * sizeof(Value);
    encoder_.write(&bytes, sizeof bytes);
  }

  // `n` values laid out contiguously in memory from `data`.
  void put(const void* data, std::uint64_t n) {
    if (n > count_ - written_) throw mismatch(written_ + n);
    written_ += n;
    encoder_.write(data, static_cast<std::size_t>(n * sizeof(Value)));
  }
  void put(Value value) { put(&value, 1); }
  void put_repeated(Value value, std::uint64_t n) {
    std::array<Value, 1024> run;
    run.fill(value);
    for (std::uint64_t left = n; left > 0;) {
      const std::uint64_t take = std::min<std::uint64_t>(left, run.size());
      put(run.data(), take);
      left -= take;
    }
  }

  void close() {
    if (written_ != count_) throw mismatch(written_);
    encoder_.finish();
    out_ << '\n' << indent_ << "</DataArray>\n";
  }

private:
  FormatError mismatch(std::uint64_t values) const {
    return FormatError("VTP array '" + std::string(name_) + "': " + std::to_string(values) +
                           " values to write, its byte count announced " + std::to_string(count_),
                       {}, "the index and a stored surface disagree; 'geotandem store check' verifies the store");
  }

  std::ostream& out_;
  const char* indent_;
  const char* name_;
  std::uint64_t count_;
  std::uint64_t written_ = 0;
  Base64Writer encoder_;
};

// One tuple per body.
template <class Value>
void field_array(std::ostream& out, SurfaceSource& source, const char* name, Value (*get)(const ComponentRow&)) {
  BinaryArray<Value> array(out, "      ", name, source.size(),
                           " NumberOfTuples=\"" + std::to_string(source.size()) + "\"");
  for (std::size_t i = 0; i < source.size(); ++i)
    array.put(get(source.row(i)));
  array.close();
}

// The body's value on each of its triangles.
template <class Value>
void cell_array(std::ostream& out, SurfaceSource& source, std::uint64_t polys, const char* name,
                Value (*get)(const ComponentRow&, std::size_t)) {
  BinaryArray<Value> array(out, "        ", name, polys);
  for (std::size_t i = 0; i < source.size(); ++i)
    array.put_repeated(get(source.row(i), i), source.triangle_count(i));
  array.close();
}

void points_array(std::ostream& out, SurfaceSource& source, std::uint64_t points) {
  BinaryArray<double> array(out, "        ", "Points", 3 * points, " NumberOfComponents=\"3\"");
  for (std::size_t i = 0; i < source.size(); ++i) {
    const auto& surface = source.surface(i);
    array.put(surface.points.data(), 3 * std::uint64_t{surface.points.size()});
  }
  array.close();
}

// Three indices per triangle, into the points of every component before it and its own.
template <class Index> void connectivity_array(std::ostream& out, SurfaceSource& source, std::uint64_t polys) {
  BinaryArray<Index> array(out, "        ", "connectivity", 3 * polys);
  std::array<Index, std::size_t{3} * 1024> chunk;
  std::uint64_t base = 0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const auto& surface = source.surface(i);
    std::size_t used = 0;
    for (const auto& t : surface.triangles) {
      for (auto v : t)
        chunk[used++] = static_cast<Index>(base + v);
      if (used == chunk.size()) {
        array.put(chunk.data(), used);
        used = 0;
      }
    }
    array.put(chunk.data(), used);
    base += surface.points.size();
  }
  array.close();
}

// Where each triangle's indices end in the connectivity: 3, 6, 9...
template <class Index> void offsets_array(std::ostream& out, std::uint64_t polys) {
  BinaryArray<Index> array(out, "        ", "offsets", polys);
  std::array<Index, 1024> chunk;
  for (std::uint64_t first = 0; first < polys; first += chunk.size()) {
    const std::uint64_t n = std::min<std::uint64_t>(chunk.size(), polys - first);
    for (std::uint64_t c = 0; c < n; ++c)
      chunk[c] = static_cast<Index>(3 * (first + c + 1));
    array.put(chunk.data(), n);
  }
  array.close();
}

template <class Index> void polys_arrays(std::ostream& out, SurfaceSource& source, std::uint64_t polys) {
  connectivity_array<Index>(out, source, polys);
  offsets_array<Index>(out, polys);
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

int vtp_index_bits(std::uint64_t points, std::uint64_t polys) {
  constexpr std::uint64_t int32_max = 2147483647;
  return points <= int32_max && 3 * polys <= int32_max ? 32 : 64;
}

namespace {

// A string array of one tuple, binary like every other array: as vtkXMLWriter writes a
// vtkStringArray, the string's characters ended by 0, after the UInt64 byte count.
void string_array(std::ostream& out, const char* name, const std::string& value) {
  out << "      <Array type=\"String\" Name=\"" << name << "\" NumberOfTuples=\"1\" format=\"binary\">\n        ";
  Base64Writer encoder(out);
  const std::uint64_t bytes = value.size() + 1;
  encoder.write(&bytes, sizeof bytes);
  encoder.write(value.c_str(), value.size() + 1); // with its terminating 0
  encoder.finish();
  out << "\n      </Array>\n";
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
  field_array<std::uint64_t>(out, source, "key", key_of);
  field_array<double>(out, source, "volume", volume_of);
  field_array<double>(out, source, "azimuth", azimuth_of);
  const volume::Geometry& geometry = source.store().geometry();
  const std::string xy = geometry.crs.empty() ? std::string("m") : geometry.crs.unit;
  string_array(out, "crs", geometry.crs.label());
  string_array(out, "crs_wkt", geometry.crs.wkt);
  string_array(out, "crs_units", xy + " " + xy + " " + volume::to_string(geometry.z_unit));
  out << "    </FieldData>\n    <Piece NumberOfPoints=\"" << points
      << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"" << polys << "\">\n";
  out << "      <CellData Scalars=\"volume\">\n";
  cell_array<std::uint64_t>(out, source, polys, "key", [](const ComponentRow& r, std::size_t) { return r.key; });
  cell_array<double>(out, source, polys, "volume", [](const ComponentRow& r, std::size_t) { return r.stats.volume; });
  cell_array<double>(out, source, polys, "azimuth", [](const ComponentRow& r, std::size_t) { return r.stats.azimuth; });
  cell_array<std::uint32_t>(out, source, polys, "body",
                            [](const ComponentRow&, std::size_t i) { return static_cast<std::uint32_t>(i); });
  out << "      </CellData>\n      <Points>\n";
  points_array(out, source, points);
  out << "      </Points>\n      <Polys>\n";
  if (vtp_index_bits(points, polys) == 32)
    polys_arrays<std::int32_t>(out, source, polys);
  else
    polys_arrays<std::int64_t>(out, source, polys);
  out << "      </Polys>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
}

} // namespace geotandem::store::detail
