// Index rows: commit, lookups, filtered queries and record reads.

#include <variant>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/component.hpp"
#include "record.hpp"
#include "row_checksum.hpp"
#include "store_impl.hpp"

namespace geotandem::store {

using namespace detail;

namespace {

// Column order shared by INSERT and SELECT.
constexpr const char* columns =
    "key, shard, byte_offset, byte_length, checksum, vertex_count, triangle_count, volume, area,"
    " centroid_x, centroid_y, centroid_z, min_x, min_y, min_z, max_x, max_y, max_z,"
    " obb_center_x, obb_center_y, obb_center_z, obb_axis0_x, obb_axis0_y, obb_axis0_z,"
    " obb_axis1_x, obb_axis1_y, obb_axis1_z, obb_axis2_x, obb_axis2_y, obb_axis2_z,"
    " obb_half0, obb_half1, obb_half2, azimuth, dip, elongation, closed, cut_by_border, run, cut_faces, cap_area,"
    " row_checksum, samples";
constexpr int column_count = 43;

// The columns to select: an index written before caps has no cut_faces and cap_area, one written
// before row checksums no row_checksum (read-only stores are not upgraded; see
// detail::upgrade_cap_columns), so those read as their defaults (NULL: no checksum to verify).
// An index written before volumes in samples has no samples column (NULL: not counted).
std::string select_columns(bool cap_columns, bool row_checksums, bool samples) {
  if (cap_columns && row_checksums && samples) return columns;
  std::string text = columns;
  text = text.substr(0, text.rfind(", samples"));
  if (!cap_columns) return text.substr(0, text.rfind(", cut_faces")) + ", '', 0.0, NULL, NULL";
  if (!row_checksums) text = text.substr(0, text.rfind(",")) + ", NULL";
  return text + (samples ? ", samples" : ", NULL");
}

void bind_entry(Statement& s, const IndexEntry& e) {
  const auto& st = e.stats;
  const auto& l = e.location;
  int i = 1;
  auto put = [&](auto value) { s.bind(i++, value); };
  put(to_sql(e.key));
  put(l.shard);
  put(to_sql(l.offset));
  put(to_sql(l.length));
  put(to_sql(l.checksum));
  put(to_sql(l.vertex_count));
  put(to_sql(l.triangle_count));
  put(st.volume);
  put(st.area);
  for (double v : st.centroid)
    put(v);
  for (double v : st.box_min)
    put(v);
  for (double v : st.box_max)
    put(v);
  for (double v : st.obb_center)
    put(v);
  for (const auto& axis : st.obb_axes)
    for (double v : axis)
      put(v);
  for (double v : st.obb_half_extents)
    put(v);
  put(st.azimuth);
  put(st.dip);
  put(st.elongation);
  put(std::int64_t{st.closed});
  put(std::int64_t{st.cut_by_border});
  put(e.run);
  put(mesh::cut_faces_text(st.cut_faces));
  put(st.cap_area);
  put(to_sql(row_checksum(e.key, l, st, e.run, true)));
  put(st.samples);
}

ComponentRow read_row(const Statement& s) {
  ComponentRow row;
  int i = 0;
  row.key = from_sql(s.column_int(i++));
  auto& l = row.location;
  l.shard = s.column_text(i++);
  l.offset = from_sql(s.column_int(i++));
  l.length = from_sql(s.column_int(i++));
  l.checksum = from_sql(s.column_int(i++));
  l.vertex_count = from_sql(s.column_int(i++));
  l.triangle_count = from_sql(s.column_int(i++));
  auto& st = row.stats;
  st.vertex_count = l.vertex_count;
  st.triangle_count = l.triangle_count;
  st.volume = s.column_double(i++);
  st.area = s.column_double(i++);
  for (double& v : st.centroid)
    v = s.column_double(i++);
  for (double& v : st.box_min)
    v = s.column_double(i++);
  for (double& v : st.box_max)
    v = s.column_double(i++);
  for (double& v : st.obb_center)
    v = s.column_double(i++);
  for (auto& axis : st.obb_axes)
    for (double& v : axis)
      v = s.column_double(i++);
  for (double& v : st.obb_half_extents)
    v = s.column_double(i++);
  st.azimuth = s.column_double(i++);
  st.dip = s.column_double(i++);
  st.elongation = s.column_double(i++);
  st.closed = s.column_int(i++) != 0;
  st.cut_by_border = s.column_int(i++) != 0;
  if (!s.column_is_null(i)) row.run = s.column_int(i);
  ++i;
  st.cut_faces = mesh::parse_cut_faces(s.column_text(i++));
  st.cap_area = s.column_double(i++);
  if (!s.column_is_null(i)) row.row_checksum = from_sql(s.column_int(i));
  ++i;
  row.samples_counted = !s.column_is_null(i);
  if (row.samples_counted) st.samples = s.column_int(i);
  return row;
}

using Value = std::variant<std::int64_t, double, std::string>;

struct Filter {
  std::string where; // " WHERE ..." or empty
  std::vector<Value> values;
};

void check_range(const auto& min, const auto& max, const char* what) {
  if (min && max && *min > *max)
    throw InvalidArgument(std::string("the minimum ") + what + " is above the maximum", {}, "swap the two bounds");
}

Filter build_filter(const Query& q) {
  check_range(q.min_volume, q.max_volume, "volume");
  check_range(q.min_vertices, q.max_vertices, "vertex count");
  check_range(q.min_triangles, q.max_triangles, "triangle count");
  if (q.sort == SortKey::selection && q.selection.empty())
    throw InvalidArgument("sorting by selection order needs a selection", {}, "name the selection to list");
  Filter f;
  // ?1 is always the selection name (possibly unused), so the filter and the order can share it.
  f.values.push_back(q.selection);
  std::vector<std::string> terms;
  // Placeholders are numbered explicitly (?2, ?3, ...) so that ?1, the selection name, may appear
  // anywhere in the statement (in the filter and in ORDER BY).
  auto add = [&](const std::string& term, std::vector<Value> values) {
    std::string numbered;
    std::size_t next = 0;
    for (char c : term) {
      numbered += c;
      if (c == '?') {
        numbered += std::to_string(f.values.size() + 1);
        f.values.push_back(std::move(values.at(next++)));
      }
    }
    terms.push_back(std::move(numbered));
  };
  if (q.min_volume) add("volume >= ?", {*q.min_volume});
  if (q.max_volume) add("volume <= ?", {*q.max_volume});
  if (q.azimuth) {
    if (q.azimuth->from <= q.azimuth->to)
      add("azimuth BETWEEN ? AND ?", {q.azimuth->from, q.azimuth->to});
    else
      add("(azimuth >= ? OR azimuth <= ?)", {q.azimuth->from, q.azimuth->to});
  }
  if (q.box) {
    const auto& b = *q.box;
    add("max_x >= ? AND min_x <= ? AND max_y >= ? AND min_y <= ? AND max_z >= ? AND min_z <= ?",
        {b.min[0], b.max[0], b.min[1], b.max[1], b.min[2], b.max[2]});
  }
  if (q.min_vertices) add("vertex_count >= ?", {to_sql(*q.min_vertices)});
  if (q.max_vertices) add("vertex_count <= ?", {to_sql(*q.max_vertices)});
  if (q.min_triangles) add("triangle_count >= ?", {to_sql(*q.min_triangles)});
  if (q.max_triangles) add("triangle_count <= ?", {to_sql(*q.max_triangles)});
  if (q.closed_only) add("closed = 1 AND cut_by_border = 0", {});
  if (q.run) add("run = ?", {*q.run});
  if (!q.selection.empty()) terms.push_back("key IN (SELECT key FROM selection_members WHERE selection = ?1)");
  for (std::size_t i = 0; i < terms.size(); ++i)
    f.where += (i == 0 ? " WHERE " : " AND ") + terms[i];
  return f;
}

void bind_values(Statement& s, const std::vector<Value>& values) {
  // A statement without any placeholder has no slot for the (unused) selection name.
  const int slots = s.parameter_count();
  for (int i = 1; i <= slots && i <= static_cast<int>(values.size()); ++i)
    std::visit([&](const auto& x) { s.bind(i, x); }, values[static_cast<std::size_t>(i - 1)]);
}

std::string order_by(const Query& q) {
  const char* direction = q.descending ? " DESC" : " ASC";
  switch (q.sort) {
  case SortKey::volume: return std::string(" ORDER BY volume") + direction + ", key ASC";
  case SortKey::azimuth: return std::string(" ORDER BY azimuth") + direction + ", key ASC";
  case SortKey::selection:
    return std::string(" ORDER BY (SELECT position FROM selection_members m WHERE m.selection = ?1 AND m.key = "
                       "components.key)") +
           direction;
  case SortKey::key: break;
  }
  return std::string(" ORDER BY key") + direction;
}

void check_selection_exists(Database& db, const std::string& name, const std::filesystem::path& dir) {
  if (name.empty()) return;
  auto s = db.prepare("SELECT count(*) FROM selections WHERE name = ?");
  s.bind(1, name);
  if (s.step() && s.column_int(0) == 1) return;
  std::string known;
  auto all = db.prepare("SELECT name FROM selections ORDER BY name");
  while (all.step())
    known += (known.empty() ? "" : ", ") + all.column_text(0);
  throw InvalidArgument("no selection named '" + name + "' in the store", {dir.string()},
                        known.empty() ? "the store has no selections" : "known selections: " + known);
}

} // namespace

std::size_t ComponentStore::commit(const std::vector<IndexEntry>& entries) {
  impl_->require_writable("commit components");
  for (const auto& e : entries) {
    validate_writer_name(e.location.shard);
    auto length = record_length(e.location.vertex_count, e.location.triangle_count);
    if (!length || *length != e.location.length || e.location.vertex_count == 0 || e.location.triangle_count == 0)
      throw InvalidArgument("component " + std::to_string(e.key) + ": the record location's length and counts disagree",
                            {impl_->dir.string()});
  }
  auto& db = *impl_->db;
  Transaction transaction(db);
  auto insert = db.prepare(std::string("INSERT OR IGNORE INTO components(") + columns + ") VALUES(?" + [] {
    std::string more;
    for (int i = 1; i < column_count; ++i)
      more += ",?";
    return more;
  }() + ")");
  auto remove = db.prepare("DELETE FROM components WHERE key = ?");
  std::size_t added = 0;
  for (const auto& e : entries) {
    if (e.replace) {
      // The old row points at a damaged record; selections that name the key keep naming it.
      db.exec("PRAGMA defer_foreign_keys=ON");
      remove.reset();
      remove.bind(1, to_sql(e.key));
      remove.run();
    }
    insert.reset();
    bind_entry(insert, e);
    insert.run();
    added += static_cast<std::size_t>(db.changes());
  }
  transaction.commit();
  return added;
}

bool ComponentStore::contains(std::uint64_t key) const {
  detail::Statement& s = impl_->cached(impl_->key_lookup, [] { return "SELECT 1 FROM components WHERE key = ?"; });
  s.bind(1, to_sql(key));
  const bool found = s.step();
  s.reset();
  return found;
}

std::vector<std::uint64_t> ComponentStore::present(const std::vector<std::uint64_t>& keys) const {
  std::vector<std::uint64_t> out;
  if (keys.empty()) return out;
  auto s = impl_->db->prepare("SELECT 1 FROM components WHERE key = ?");
  for (std::uint64_t key : keys) {
    s.reset();
    s.bind(1, to_sql(key));
    if (s.step()) out.push_back(key);
  }
  return out;
}

std::uint64_t ComponentStore::size() const {
  auto s = impl_->db->prepare("SELECT count(*) FROM components");
  s.step();
  return from_sql(s.column_int(0));
}

std::uint64_t ComponentStore::indexed_end(const std::string& shard) const {
  auto s = impl_->db->prepare(
      "SELECT byte_offset + byte_length FROM components WHERE shard = ? ORDER BY byte_offset DESC LIMIT 1");
  s.bind(1, shard);
  return s.step() ? from_sql(s.column_int(0)) : 0;
}

std::vector<ComponentRow> ComponentStore::query(const Query& q) const {
  check_selection_exists(*impl_->db, q.selection, impl_->dir);
  auto filter = build_filter(q);
  std::string sql = "SELECT " + select_columns(impl_->cap_columns, impl_->row_checksums, impl_->samples_column) +
                    " FROM components" + filter.where + order_by(q);
  if (q.limit) sql += " LIMIT " + std::to_string(std::min<std::uint64_t>(*q.limit, INT64_MAX));
  auto s = impl_->db->prepare(sql);
  bind_values(s, filter.values);
  std::vector<ComponentRow> rows;
  while (s.step())
    rows.push_back(read_row(s));
  return rows;
}

std::uint64_t ComponentStore::count(const Query& q) const {
  check_selection_exists(*impl_->db, q.selection, impl_->dir);
  auto filter = build_filter(q);
  auto s = impl_->db->prepare("SELECT count(*) FROM components" + filter.where);
  bind_values(s, filter.values);
  s.step();
  return from_sql(s.column_int(0));
}

std::optional<ComponentRow> ComponentStore::find(std::uint64_t key) const {
  detail::Statement& s = impl_->cached(impl_->row_lookup, [this] {
    return "SELECT " + select_columns(impl_->cap_columns, impl_->row_checksums, impl_->samples_column) +
           " FROM components WHERE key = ?";
  });
  s.bind(1, to_sql(key));
  std::optional<ComponentRow> row;
  if (s.step()) row = read_row(s);
  s.reset();
  return row;
}

mesh::SurfaceMesh ComponentStore::read(std::uint64_t key) const {
  auto row = find(key);
  if (!row)
    throw InvalidArgument("no component with key " + std::to_string(key) + " in the store", {impl_->dir.string()},
                          "list the keys with 'geotandem store ls'");
  return read(*row);
}

mesh::SurfaceMesh ComponentStore::read(const ComponentRow& row) const {
  // The row first: a measure changed in the index is as damaged as a changed record.
  if (row.row_checksum &&
      *row.row_checksum != row_checksum(row.key, row.location, row.stats, row.run, row.samples_counted))
    throw FormatError("component " + std::to_string(row.key) +
                          ": its index row does not match the row's checksum (a measure, its record's place or its "
                          "run was changed in the index)",
                      {impl_->db->path()}, "rerun the same extraction into this store to write it again");
  const auto& file = impl_->shard_for_reading(row.location.shard);
  return read_record_from(file.get(), shard_path(impl_->dir, row.location.shard), row.location, row.key);
}

} // namespace geotandem::store
