// What a store's components were made from. A run's parameters may hold an "identity" object
// (isovalue, extraction settings, input fingerprint, attribute chain); a new run that would mix
// components of another identity into the store is refused with the list of differences.

#include <set>

#include "geotandem/core/error.hpp"
#include "store_impl.hpp"

namespace geotandem::store {

using namespace detail;

namespace {

std::string shown(const nlohmann::json* value) {
  if (!value) return "(not recorded)";
  std::string text = value->is_string() ? value->get<std::string>() : value->dump();
  if (text.size() > 200) text = text.substr(0, 197) + "...";
  return text;
}

void compare(const std::string& prefix, const nlohmann::json& stored, const nlohmann::json& now,
             std::vector<std::string>& out) {
  std::set<std::string> keys;
  for (const auto& [key, value] : stored.items())
    keys.insert(key);
  for (const auto& [key, value] : now.items())
    keys.insert(key);
  for (const auto& key : keys) {
    const nlohmann::json* a = stored.contains(key) ? &stored[key] : nullptr;
    const nlohmann::json* b = now.contains(key) ? &now[key] : nullptr;
    if (a && b && *a == *b) continue;
    if (a && b && a->is_object() && b->is_object()) {
      compare(prefix + key + ".", *a, *b, out);
      continue;
    }
    out.push_back(prefix + key + ": " + shown(a) + " in the store, " + shown(b) + " now");
  }
}

} // namespace

std::vector<std::string> ComponentStore::resume_differences(const std::string& identity_json) const {
  auto identity = parse_json_argument(identity_json, "the run identity");
  auto statement = impl_->db->prepare("SELECT parameters FROM runs ORDER BY id DESC");
  while (statement.step()) {
    auto parameters = nlohmann::json::parse(statement.column_text(0), nullptr, false);
    if (parameters.is_discarded() || !parameters.is_object() || !parameters.contains("identity")) continue;
    std::vector<std::string> differences;
    compare("", parameters["identity"], identity, differences);
    return differences;
  }
  return {};
}

std::int64_t ComponentStore::begin_run(const std::string& parameters_json) {
  impl_->require_writable("begin a run");
  auto parameters = parse_json_argument(parameters_json, "the run parameters");
  if (parameters.is_object() && parameters.contains("identity")) {
    auto differences = resume_differences(parameters["identity"].dump());
    if (!differences.empty()) {
      std::string list;
      for (const auto& d : differences)
        list += "\n  " + d;
      throw InvalidArgument("the store holds components of another extraction; resuming would mix them. "
                            "What differs:" +
                                list + "\n",
                            {impl_->dir.string()},
                            "write to another --out, or pass --fresh to replace the store with this run");
    }
  }
  auto& db = *impl_->db;
  db.prepare("INSERT INTO runs(parameters, started) VALUES(?, ?)").bind(1, parameters.dump()).bind(2, utc_now()).run();
  return sqlite3_last_insert_rowid(db.handle());
}

} // namespace geotandem::store
