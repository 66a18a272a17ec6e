// The index schema (docs/store-format.md lists every column and its unit).

#include "geotandem/core/error.hpp"
#include "store_impl.hpp"

namespace geotandem::store::detail {

void configure_connection(Database& db, bool writable) {
  if (writable) {
    // WAL lets readers list the store while a run writes it; FULL makes a committed row survive a
    // power cut, not only a process kill.
    db.exec("PRAGMA journal_mode=WAL");
    db.exec("PRAGMA synchronous=FULL");
  }
  db.exec("PRAGMA foreign_keys=ON");
}

void create_schema(Database& db) {
  Transaction transaction(db);
  db.exec(R"sql(
CREATE TABLE meta(name TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE runs(
  id INTEGER PRIMARY KEY AUTOINCREMENT,
  parameters TEXT NOT NULL,
  started TEXT NOT NULL,
  ended TEXT,
  statistics TEXT NOT NULL DEFAULT '{}');
CREATE TABLE components(
  key INTEGER PRIMARY KEY,
  shard TEXT NOT NULL, byte_offset INTEGER NOT NULL, byte_length INTEGER NOT NULL, checksum INTEGER NOT NULL,
  vertex_count INTEGER NOT NULL, triangle_count INTEGER NOT NULL,
  volume REAL NOT NULL, area REAL NOT NULL,
  centroid_x REAL NOT NULL, centroid_y REAL NOT NULL, centroid_z REAL NOT NULL,
  min_x REAL NOT NULL, min_y REAL NOT NULL, min_z REAL NOT NULL,
  max_x REAL NOT NULL, max_y REAL NOT NULL, max_z REAL NOT NULL,
  obb_center_x REAL NOT NULL, obb_center_y REAL NOT NULL, obb_center_z REAL NOT NULL,
  obb_axis0_x REAL NOT NULL, obb_axis0_y REAL NOT NULL, obb_axis0_z REAL NOT NULL,
  obb_axis1_x REAL NOT NULL, obb_axis1_y REAL NOT NULL, obb_axis1_z REAL NOT NULL,
  obb_axis2_x REAL NOT NULL, obb_axis2_y REAL NOT NULL, obb_axis2_z REAL NOT NULL,
  obb_half0 REAL NOT NULL, obb_half1 REAL NOT NULL, obb_half2 REAL NOT NULL,
  azimuth REAL NOT NULL, dip REAL NOT NULL, elongation REAL NOT NULL,
  closed INTEGER NOT NULL, cut_by_border INTEGER NOT NULL,
  run INTEGER REFERENCES runs(id),
  cut_faces TEXT NOT NULL DEFAULT '', cap_area REAL NOT NULL DEFAULT 0,
  row_checksum INTEGER, samples INTEGER);
CREATE INDEX components_volume ON components(volume);
CREATE INDEX components_azimuth ON components(azimuth);
CREATE INDEX components_shard ON components(shard, byte_offset);
CREATE INDEX components_run ON components(run);
CREATE TABLE selections(name TEXT PRIMARY KEY, parameters TEXT NOT NULL, created TEXT NOT NULL);
CREATE TABLE selection_members(
  selection TEXT NOT NULL REFERENCES selections(name) ON DELETE CASCADE,
  key INTEGER NOT NULL REFERENCES components(key),
  position INTEGER NOT NULL,
  PRIMARY KEY(selection, key)) WITHOUT ROWID;
)sql");
  db.prepare("INSERT INTO meta(name, value) VALUES('schema_version', ?)")
      .bind(1, std::to_string(index_schema_version))
      .run();
  transaction.commit();
}

void check_schema(Database& db) {
  auto tables = db.prepare("SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = 'meta'");
  if (!tables.step() || tables.column_int(0) != 1)
    throw FormatError("the index has no meta table", {db.path()}, "the file is not a geotandem store index");
  auto statement = db.prepare("SELECT value FROM meta WHERE name = 'schema_version'");
  if (!statement.step())
    throw FormatError("the index has no schema version", {db.path()}, "the file is not a geotandem store index");
  auto version = statement.column_text(0);
  if (version != std::to_string(index_schema_version))
    throw FormatError("the index has schema version " + version + "; this build reads version " +
                          std::to_string(index_schema_version),
                      {db.path()}, "open the store with the geotandem version that wrote it");
}

bool upgrade_cap_columns(Database& db, bool writable) {
  auto columns = db.prepare("SELECT count(*) FROM pragma_table_info('components') WHERE name = 'cut_faces'");
  if (columns.step() && columns.column_int(0) == 1) return true;
  if (!writable) return false;
  db.exec("ALTER TABLE components ADD COLUMN cut_faces TEXT NOT NULL DEFAULT ''");
  db.exec("ALTER TABLE components ADD COLUMN cap_area REAL NOT NULL DEFAULT 0");
  return true;
}

bool upgrade_row_checksum_column(Database& db, bool writable) {
  auto columns = db.prepare("SELECT count(*) FROM pragma_table_info('components') WHERE name = 'row_checksum'");
  if (columns.step() && columns.column_int(0) == 1) return true;
  if (!writable) return false;
  // NULL in the rows already there: they were never checksummed, and a checksum made now would
  // vouch for whatever they hold.
  db.exec("ALTER TABLE components ADD COLUMN row_checksum INTEGER");
  return true;
}

bool upgrade_samples_column(Database& db, bool writable) {
  auto columns = db.prepare("SELECT count(*) FROM pragma_table_info('components') WHERE name = 'samples'");
  if (columns.step() && columns.column_int(0) == 1) return true;
  if (!writable) return false;
  // NULL in the rows already there: their samples were not counted (issue 54).
  db.exec("ALTER TABLE components ADD COLUMN samples INTEGER");
  return true;
}

} // namespace geotandem::store::detail
