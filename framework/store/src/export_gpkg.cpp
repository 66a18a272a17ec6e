// The inventory as a GIS layer: a GeoPackage with each body's footprint (polygons) and centroid
// (points), every measure of the index as attributes, in the store's CRS (export.hpp). GDAL writes
// it (volume/geopackage.hpp, through the GDAL module); this file decides what goes in.

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <limits>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "export_writers.hpp"
#include "file_io.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/volume/geopackage.hpp"

namespace geotandem::store::detail {
namespace {

using volume::GisField;
using volume::GisFieldType;
using volume::GisValue;

// The attribute columns, in the order of values_of (the fields of `store ls --json`, less where
// the record lies, with vectors split into _x/_y/_z as the Python DataFrame has them). GeoPackage
// integers are signed 64-bit: keys at or above 2^63 (possible in cubes of about 2^21 samples an
// axis) make the key column text, so that no key turns negative.
std::vector<GisField> measure_fields(bool text_key) {
  std::vector<GisField> f = {{"key", text_key ? GisFieldType::text : GisFieldType::integer},
                             {"vertex_count", GisFieldType::integer},
                             {"triangle_count", GisFieldType::integer},
                             {"volume", GisFieldType::real},
                             {"area", GisFieldType::real},
                             {"footprint_area", GisFieldType::real}};
  auto triple = [&](const std::string& name) {
    for (const char* axis : {"_x", "_y", "_z"})
      f.push_back({name + axis, GisFieldType::real});
  };
  triple("centroid");
  triple("box_min");
  triple("box_max");
  triple("obb_center");
  for (int a = 0; a < 3; ++a)
    triple("obb_axis" + std::to_string(a));
  for (int a = 0; a < 3; ++a)
    f.push_back({"obb_half_extent" + std::to_string(a), GisFieldType::real});
  f.push_back({"azimuth", GisFieldType::real});
  f.push_back({"dip", GisFieldType::real});
  f.push_back({"elongation", GisFieldType::real});
  f.push_back({"closed", GisFieldType::boolean});
  f.push_back({"cut_by_border", GisFieldType::boolean});
  f.push_back({"cut_faces", GisFieldType::text});
  f.push_back({"cap_area", GisFieldType::real});
  f.push_back({"run", GisFieldType::integer});
  return f;
}

// Built value by value: brace lists of variants holding strings trip GCC 12's maybe-uninitialized
// warning at -O3.
std::vector<GisValue> values_of(const ComponentRow& row, double footprint_area, bool text_key) {
  const mesh::ComponentStats& s = row.stats;
  std::vector<GisValue> v;
  v.reserve(48);
  if (text_key)
    v.emplace_back(std::in_place_type<std::string>, std::to_string(row.key));
  else
    v.emplace_back(std::in_place_type<std::int64_t>, static_cast<std::int64_t>(row.key));
  v.emplace_back(std::in_place_type<std::int64_t>, static_cast<std::int64_t>(row.location.vertex_count));
  v.emplace_back(std::in_place_type<std::int64_t>, static_cast<std::int64_t>(row.location.triangle_count));
  auto real = [&](double value) { v.emplace_back(std::in_place_type<double>, value); };
  real(s.volume);
  real(s.area);
  real(footprint_area);
  auto triple = [&](const std::array<double, 3>& a) {
    for (double value : a)
      real(value);
  };
  triple(s.centroid);
  triple(s.box_min);
  triple(s.box_max);
  triple(s.obb_center);
  for (const auto& axis : s.obb_axes)
    triple(axis);
  triple(s.obb_half_extents);
  real(s.azimuth);
  real(s.dip);
  real(s.elongation);
  v.emplace_back(std::in_place_type<bool>, s.closed);
  v.emplace_back(std::in_place_type<bool>, s.cut_by_border);
  v.emplace_back(std::in_place_type<std::string>, mesh::cut_faces_text(s.cut_faces));
  real(s.cap_area);
  if (row.run)
    v.emplace_back(std::in_place_type<std::int64_t>, *row.run);
  else
    v.emplace_back();
  return v;
}

// The body seen from above: the union of its triangles projected on the map. For a closed surface
// the triangles facing one way (up or down) cover the whole outline, each point of it once or more,
// so only those are merged (half the work); an open surface gives all of its triangles.
std::vector<volume::MapPolygon> footprint_of(const mesh::SurfaceMesh& surface, bool closed) {
  std::vector<volume::MapTriangle> triangles;
  triangles.reserve(closed ? surface.triangles.size() / 2 + 1 : surface.triangles.size());
  for (const auto& t : surface.triangles) {
    const auto& a = surface.points[t[0]];
    const auto& b = surface.points[t[1]];
    const auto& c = surface.points[t[2]];
    const double twice = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    if (closed && !(twice > 0.0)) continue;
    triangles.push_back({{{a[0], a[1]}, {b[0], b[1]}, {c[0], c[1]}}});
  }
  return volume::union_of_triangles(triangles);
}

// A unique name beside `target` for GDAL to create (it refuses an existing file, so the name is
// reserved with mkstemps and freed just before), removed unless committed.
class TemporaryName {
public:
  explicit TemporaryName(const std::filesystem::path& target) {
    const auto dir = target.parent_path().empty() ? std::filesystem::path(".") : target.parent_path();
    const std::string pattern = (dir / ("." + target.filename().string() + ".XXXXXX.gpkg")).string();
    std::vector<char> name(pattern.begin(), pattern.end());
    name.push_back('\0');
    const int fd = ::mkstemps(name.data(), 5);
    if (fd < 0)
      throw IoError("cannot create a file in the directory: " + errno_text(errno), {dir.string()},
                    "check that the directory exists and is writable");
    ::close(fd);
    path_ = name.data();
    std::filesystem::remove(path_);
  }
  ~TemporaryName() {
    if (committed_) return;
    std::error_code ec;
    std::filesystem::remove(path_, ec);
    std::filesystem::remove(path_.string() + "-journal", ec);
  }
  TemporaryName(const TemporaryName&) = delete;
  TemporaryName& operator=(const TemporaryName&) = delete;
  const std::filesystem::path& path() const { return path_; }

  // Syncs the file, renames it over `target` and syncs the directory.
  void commit(const std::filesystem::path& target) {
    FileHandle file(::open(path_.c_str(), O_RDONLY | O_CLOEXEC));
    if (file.get() < 0) throw IoError("cannot open the GeoPackage to flush it: " + errno_text(errno), {path_.string()});
    sync_data(file.get(), path_);
    if (::rename(path_.c_str(), target.c_str()) != 0)
      throw IoError("cannot move the GeoPackage into place: " + errno_text(errno), {target.string()});
    committed_ = true;
    sync_directory(target.parent_path().empty() ? std::filesystem::path(".") : target.parent_path());
  }

private:
  std::filesystem::path path_;
  bool committed_ = false;
};

} // namespace

void write_gpkg(const ComponentStore& store, const std::vector<const ComponentRow*>& rows,
                const std::filesystem::path& path, const ExportOptions& options, const std::function<void()>& tick) {
  const bool text_key = std::any_of(rows.begin(), rows.end(), [](const ComponentRow* row) {
    return row->key > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
  });
  volume::GeoPackageLayout layout;
  layout.fields = measure_fields(text_key);
  layout.crs = store.geometry().crs;
  layout.description = "geotandem bodies of " + store.directory().string() +
                       (options.selection.empty() ? std::string() : ", selection " + options.selection) +
                       "; CRS: " + layout.crs.label() + "; volumes in " + volume::volume_unit(store.geometry());
  // Without a selection filter, each selection of the store is a column: in_<name>.
  std::vector<std::set<std::uint64_t>> members;
  if (options.selection.empty())
    for (const SelectionSummary& summary : store.selections()) {
      layout.fields.push_back({"in_" + summary.name, GisFieldType::boolean});
      const Selection selection = store.load_selection(summary.name);
      members.emplace_back(selection.keys.begin(), selection.keys.end());
    }
  TemporaryName temporary(path);
  auto writer = volume::create_geopackage(temporary.path().string(), layout);
  for (const ComponentRow* row : rows) {
    const mesh::SurfaceMesh surface = store.read(*row);
    const auto footprint = footprint_of(surface, row->stats.closed);
    std::vector<GisValue> values = values_of(*row, volume::area_of(footprint), text_key);
    for (const auto& keys : members)
      values.emplace_back(std::in_place_type<bool>, keys.count(row->key) > 0);
    writer->add_polygons(footprint, values);
    writer->add_point({row->stats.centroid[0], row->stats.centroid[1]}, values);
    tick();
  }
  writer->finish();
  writer.reset();
  temporary.commit(path);
}

} // namespace geotandem::store::detail
