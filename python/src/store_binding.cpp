// geotandem._core.Store: a component store opened read-only, its index as numpy columns, meshes as
// numpy arrays. Everything goes through the C++ store API (ComponentStore::query, read, check), so
// the Python package reads the index exactly as `geotandem store ls` and the exports do.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdio>
#include <mutex>

#include "bindings.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/mesh/caps.hpp"
#include "geotandem/store/check.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/volume/geometry_json.hpp"

namespace py = pybind11;

namespace geotandem::python {
namespace {

// Index columns, one numpy array (or list of str) per field of `store ls --json`, flattened:
// centroid -> centroid_x/y/z, obb axes -> obb_axis0_x ... The counts are the stored record's.
py::dict index_columns(const std::vector<store::ComponentRow>& rows) {
  const auto n = static_cast<py::ssize_t>(rows.size());
  py::array_t<std::uint64_t> key(n), vertex_count(n), triangle_count(n), offset(n), length(n);
  py::array_t<double> volume(n), area(n), azimuth(n), dip(n), elongation(n), cap_area(n);
  py::array_t<bool> closed(n), cut_by_border(n);
  py::array_t<std::int64_t> run(n), samples(n);
  py::array_t<bool> run_known(n), samples_known(n);
  const char* axes = "xyz";
  std::vector<py::array_t<double>> triples; // centroid, box_min, box_max, obb_center, 3 axes, half extents
  for (int t = 0; t < 8 * 3; ++t)
    triples.emplace_back(n);
  py::list cut_faces, shard, checksum;
  for (py::ssize_t r = 0; r < n; ++r) {
    const auto& row = rows[static_cast<std::size_t>(r)];
    const auto& s = row.stats;
    key.mutable_data()[r] = row.key;
    vertex_count.mutable_data()[r] = row.location.vertex_count;
    triangle_count.mutable_data()[r] = row.location.triangle_count;
    offset.mutable_data()[r] = row.location.offset;
    length.mutable_data()[r] = row.location.length;
    volume.mutable_data()[r] = s.volume;
    area.mutable_data()[r] = s.area;
    azimuth.mutable_data()[r] = s.azimuth;
    dip.mutable_data()[r] = s.dip;
    elongation.mutable_data()[r] = s.elongation;
    cap_area.mutable_data()[r] = s.cap_area;
    closed.mutable_data()[r] = s.closed;
    cut_by_border.mutable_data()[r] = s.cut_by_border;
    run.mutable_data()[r] = row.run.value_or(0);
    run_known.mutable_data()[r] = row.run.has_value();
    samples.mutable_data()[r] = s.samples;
    samples_known.mutable_data()[r] = row.samples_counted;
    const std::array<const std::array<double, 3>*, 8> sources{&s.centroid,    &s.box_min,         &s.box_max,
                                                              &s.obb_center,  &s.obb_axes[0],     &s.obb_axes[1],
                                                              &s.obb_axes[2], &s.obb_half_extents};
    for (std::size_t t = 0; t < sources.size(); ++t)
      for (std::size_t a = 0; a < 3; ++a)
        triples[t * 3 + a].mutable_data()[r] = (*sources[t])[a];
    cut_faces.append(mesh::cut_faces_text(s.cut_faces));
    shard.append(row.location.shard);
    char text[24];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(row.location.checksum));
    checksum.append(text);
  }
  py::dict c;
  c["key"] = key;
  c["vertex_count"] = vertex_count;
  c["triangle_count"] = triangle_count;
  c["volume"] = volume;
  c["samples"] = samples;
  c["samples_known"] = samples_known;
  c["area"] = area;
  const char* names[8] = {"centroid", "box_min", "box_max", "obb_center", "obb_axis0", "obb_axis1", "obb_axis2", ""};
  for (std::size_t t = 0; t < 7; ++t)
    for (std::size_t a = 0; a < 3; ++a)
      c[py::str(std::string(names[t]) + "_" + axes[a])] = triples[t * 3 + a];
  for (std::size_t a = 0; a < 3; ++a)
    c[py::str("obb_half_extent" + std::to_string(a))] = triples[21 + a];
  c["azimuth"] = azimuth;
  c["dip"] = dip;
  c["elongation"] = elongation;
  c["closed"] = closed;
  c["cut_by_border"] = cut_by_border;
  c["cut_faces"] = cut_faces;
  c["cap_area"] = cap_area;
  c["run"] = run;
  c["run_known"] = run_known;
  c["shard"] = shard;
  c["offset"] = offset;
  c["length"] = length;
  c["checksum"] = checksum;
  return c;
}

py::tuple mesh_arrays(const mesh::SurfaceMesh& surface) {
  py::array_t<double> vertices({static_cast<py::ssize_t>(surface.points.size()), py::ssize_t{3}});
  py::array_t<std::int64_t> triangles({static_cast<py::ssize_t>(surface.triangles.size()), py::ssize_t{3}});
  auto v = vertices.mutable_unchecked<2>();
  for (std::size_t p = 0; p < surface.points.size(); ++p)
    for (py::ssize_t a = 0; a < 3; ++a)
      v(static_cast<py::ssize_t>(p), a) = surface.points[p][static_cast<std::size_t>(a)];
  auto t = triangles.mutable_unchecked<2>();
  for (std::size_t f = 0; f < surface.triangles.size(); ++f)
    for (py::ssize_t a = 0; a < 3; ++a)
      t(static_cast<py::ssize_t>(f), a) = surface.triangles[f][static_cast<std::size_t>(a)];
  return py::make_tuple(vertices, triangles);
}

class Store {
public:
  explicit Store(const std::string& dir) : store_(store::ComponentStore::open(dir, store::OpenMode::read_only)) {}

  std::string directory() const { return store_.directory().string(); }
  std::string info_json() const { return store_.info_json(); }
  std::string geometry_json() const {
    auto j = volume::geometry_fields_json(store_.geometry());
    const auto& shape = store_.geometry().shape;
    j["shape"] = {shape[0], shape[1], shape[2]};
    return j.dump();
  }
  std::uint64_t size() const {
    std::lock_guard lock(mutex_);
    return store_.size();
  }

  // Every row, or the members of a selection in its saved order.
  py::dict columns(const std::string& selection) const {
    store::Query q;
    q.selection = selection;
    if (!selection.empty()) q.sort = store::SortKey::selection;
    std::vector<store::ComponentRow> rows;
    {
      py::gil_scoped_release release; // reading 10^5 rows takes a while
      std::lock_guard lock(mutex_);
      rows = store_.query(q);
    }
    return index_columns(rows);
  }

  py::list selections() const {
    std::lock_guard lock(mutex_);
    py::list out;
    for (const auto& s : store_.selections()) {
      py::dict d;
      d["name"] = s.name, d["size"] = s.size, d["created"] = s.created, d["parameters"] = s.parameters;
      out.append(d);
    }
    return out;
  }

  py::array_t<std::uint64_t> selection_keys(const std::string& name) const {
    std::lock_guard lock(mutex_);
    auto keys = store_.load_selection(name).keys;
    py::array_t<std::uint64_t> out(static_cast<py::ssize_t>(keys.size()));
    std::copy(keys.begin(), keys.end(), out.mutable_data());
    return out;
  }

  py::list runs() const {
    std::lock_guard lock(mutex_);
    py::list out;
    for (const auto& r : store_.runs()) {
      py::dict d;
      d["id"] = r.id, d["started"] = r.started,
      d["ended"] = r.ended.empty() ? py::object(py::none()) : py::str(r.ended);
      d["components"] = r.component_count, d["parameters"] = r.parameters, d["statistics"] = r.statistics;
      out.append(d);
    }
    return out;
  }

  // The surface of one key as the PLY export writes it: world coordinates, caps kept or left out.
  py::tuple mesh(std::uint64_t key, bool caps) const {
    mesh::SurfaceMesh surface;
    {
      py::gil_scoped_release release;
      std::lock_guard lock(mutex_);
      auto row = store_.find(key);
      if (!row)
        throw InvalidArgument("no component with key " + std::to_string(key) + " in the store",
                              {store_.directory().string()}, "list the keys with Store.components()");
      surface = store_.read(*row);
      if (!caps) surface = mesh::without_world_caps(surface, store_.geometry());
    }
    return mesh_arrays(surface);
  }

  // The damaged records, as `store check` lists them: (key, problem) pairs; keys given: those only.
  py::list check(const std::optional<std::vector<std::uint64_t>>& keys) const {
    std::vector<std::pair<std::uint64_t, std::string>> damaged;
    {
      py::gil_scoped_release release;
      std::lock_guard lock(mutex_);
      if (keys) {
        for (auto key : *keys) {
          auto row = store_.find(key);
          if (!row) throw InvalidArgument("no component with key " + std::to_string(key) + " in the store");
          if (auto problem = store::verify_component(store_, *row)) damaged.emplace_back(key, *problem);
        }
      } else {
        NullProgress progress;
        for (const auto& d : store::check_store(store_, progress, CancelToken{}).damaged)
          damaged.emplace_back(d.key, d.problem);
      }
    }
    py::list out;
    for (const auto& [key, problem] : damaged)
      out.append(py::make_tuple(key, problem));
    return out;
  }

private:
  store::ComponentStore store_;
  // ComponentStore is not thread-safe; the methods that release the GIL would let two Python
  // threads into it at once.
  mutable std::mutex mutex_;
};

} // namespace

void bind_store(py::module_& m) {
  py::class_<Store>(m, "Store", "A component store opened read-only (see geotandem.Store).")
      .def(py::init<const std::string&>(), py::arg("directory"))
      .def_property_readonly("directory", &Store::directory)
      .def("info_json", &Store::info_json)
      .def("geometry_json", &Store::geometry_json)
      .def("size", &Store::size)
      .def("columns", &Store::columns, py::arg("selection") = "")
      .def("selections", &Store::selections)
      .def("selection_keys", &Store::selection_keys, py::arg("name"))
      .def("runs", &Store::runs)
      .def("mesh", &Store::mesh, py::arg("key"), py::arg("caps") = true)
      .def("check", &Store::check, py::arg("keys") = py::none());
}

} // namespace geotandem::python
