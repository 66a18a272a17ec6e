#pragma once
// The state behind a ComponentStore, shared by the files that implement it.

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "file_io.hpp"
#include "geotandem/store/store.hpp"
#include "sqlite.hpp"

namespace geotandem::store {

struct ComponentStore::Impl {
  std::filesystem::path dir;
  volume::Geometry geometry;
  std::string info_json;
  bool writable = false;
  bool samples_column = true; // the index has the samples column (stores from before issue 54 may not)
  bool cap_columns = true;    // the index has cut_faces and cap_area (stores from before caps may not)
  bool row_checksums = true;  // the index has row_checksum (stores from before row checksums may not)
  std::unique_ptr<detail::Database> db;
  // The statements of contains() and find(), prepared once and reset after each use (so that they
  // hold no read snapshot): preparing one for every key cost hundreds of allocations in SQLite's
  // parser, and a local sink asks for every component it commits, a report for every body it shows.
  std::optional<detail::Statement> key_lookup, row_lookup;
  // `slot`'s statement, prepared on first use from the text `sql()` gives (built only then) and
  // reset, ready for its bindings.
  template <class Sql> detail::Statement& cached(std::optional<detail::Statement>& slot, Sql&& sql) {
    if (!slot) slot.emplace(db->prepare(sql()));
    slot->reset();
    return *slot;
  }
  // Shards opened for reading, by writer name; kept open across reads.
  std::map<std::string, detail::FileHandle> shards;
  // The store directory, held with an exclusive flock while the store is open for writing: one
  // writer per store, and remove() never deletes a store that a process is writing.
  detail::FileHandle writer_lock;

  const detail::FileHandle& shard_for_reading(const std::string& shard);
  void require_writable(const char* what) const;
};

namespace detail {

inline constexpr int index_schema_version = 1;

// Creates the index tables in a new database; checks the schema of an existing one (FormatError).
void create_schema(Database& db);
void check_schema(Database& db);
// Whether the components table has the cut_faces and cap_area columns; an index from before caps
// gets them (with defaults '' and 0) when it is open for writing.
bool upgrade_cap_columns(Database& db, bool writable);
// Whether the components table has the row_checksum column; an index from before row checksums
// gets it (NULL in the rows already there) when it is open for writing.
bool upgrade_row_checksum_column(Database& db, bool writable);
// The samples column (volume in samples, issue 54), added the same way; false when absent.
bool upgrade_samples_column(Database& db, bool writable);
// Per-connection settings (WAL is persistent; synchronous and foreign keys are not).
void configure_connection(Database& db, bool writable);

// Takes the store's writer lock: an exclusive flock on the directory, held by the one process
// that writes the store (and taken by removal). Throws IoError ("another process is writing this
// store", exit 3) when it cannot be had at once.
FileHandle lock_store_directory(const std::filesystem::path& dir);

// A temporary store.json left by a killed write: ".store.json.XXXXXX.tmp" (AtomicFile), or the
// fixed "store.json.tmp" of earlier versions.
inline bool is_store_json_temporary(const std::string& name) {
  return name == "store.json.tmp" ||
         (name.size() == 22 && name.rfind(".store.json.", 0) == 0 && name.compare(name.size() - 4, 4, ".tmp") == 0);
}

// The current time in UTC, ISO 8601 ("2024-05-01T12:00:00Z").
std::string utc_now();
// Parses JSON text given through the API; throws InvalidArgument naming `what`.
nlohmann::json parse_json_argument(const std::string& text, const std::string& what);

nlohmann::json geometry_to_json(const volume::Geometry& geometry);
// Throws FormatError naming `file` for a missing or ill-typed field.
volume::Geometry geometry_from_json(const nlohmann::json& j, const std::string& file);

} // namespace detail
} // namespace geotandem::store
