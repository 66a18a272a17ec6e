// Named selections: subsets of keys kept with the parameters that chose them.

#include "geotandem/core/error.hpp"
#include "store_impl.hpp"

namespace geotandem::store {

using namespace detail;

namespace {

void validate_selection_name(const std::string& name) {
  if (name.empty() || name.size() > 200)
    throw InvalidArgument("a selection name must have 1 to 200 characters, got '" + name + "'");
}

} // namespace

void ComponentStore::save_selection(const std::string& name, const std::vector<std::uint64_t>& keys,
                                    const std::string& parameters_json, bool replace) {
  impl_->require_writable("save a selection");
  validate_selection_name(name);
  auto parameters = parse_json_argument(parameters_json, "the selection parameters");
  auto& db = *impl_->db;
  Transaction transaction(db);
  {
    auto existing = db.prepare("SELECT count(*) FROM selections WHERE name = ?");
    existing.bind(1, name);
    existing.step();
    if (existing.column_int(0) > 0) {
      if (!replace)
        throw InvalidArgument("a selection named '" + name + "' already exists", {impl_->dir.string()},
                              "choose another name or replace it");
      db.prepare("DELETE FROM selection_members WHERE selection = ?").bind(1, name).run();
      db.prepare("DELETE FROM selections WHERE name = ?").bind(1, name).run();
    }
  }
  db.prepare("INSERT INTO selections(name, parameters, created) VALUES(?, ?, ?)")
      .bind(1, name)
      .bind(2, parameters.dump())
      .bind(3, utc_now())
      .run();
  auto known = db.prepare("SELECT 1 FROM components WHERE key = ?");
  auto insert = db.prepare("INSERT OR IGNORE INTO selection_members(selection, key, position) VALUES(?, ?, ?)");
  std::int64_t position = 0;
  for (auto key : keys) {
    known.reset();
    known.bind(1, to_sql(key));
    if (!known.step())
      throw InvalidArgument("selection '" + name + "' names key " + std::to_string(key) + ", which is not in the store",
                            {impl_->dir.string()});
    insert.reset();
    insert.bind(1, name).bind(2, to_sql(key)).bind(3, position++).run();
  }
  transaction.commit();
}

Selection ComponentStore::load_selection(const std::string& name) const {
  auto& db = *impl_->db;
  auto head = db.prepare("SELECT parameters, created FROM selections WHERE name = ?");
  head.bind(1, name);
  if (!head.step()) throw InvalidArgument("no selection named '" + name + "' in the store", {impl_->dir.string()});
  Selection selection;
  selection.name = name;
  selection.parameters = head.column_text(0);
  selection.created = head.column_text(1);
  auto members = db.prepare("SELECT key FROM selection_members WHERE selection = ? ORDER BY position");
  members.bind(1, name);
  while (members.step())
    selection.keys.push_back(from_sql(members.column_int(0)));
  return selection;
}

std::vector<SelectionSummary> ComponentStore::selections() const {
  auto s = impl_->db->prepare("SELECT s.name, s.parameters, s.created,"
                              " (SELECT count(*) FROM selection_members m WHERE m.selection = s.name)"
                              " FROM selections s ORDER BY s.name");
  std::vector<SelectionSummary> list;
  while (s.step())
    list.push_back({s.column_text(0), s.column_text(1), s.column_text(2), from_sql(s.column_int(3))});
  return list;
}

void ComponentStore::delete_selection(const std::string& name) {
  impl_->require_writable("delete a selection");
  auto& db = *impl_->db;
  Transaction transaction(db);
  db.prepare("DELETE FROM selection_members WHERE selection = ?").bind(1, name).run();
  db.prepare("DELETE FROM selections WHERE name = ?").bind(1, name).run();
  if (db.changes() != 1) throw InvalidArgument("no selection named '" + name + "' in the store", {impl_->dir.string()});
  transaction.commit();
}

} // namespace geotandem::store
