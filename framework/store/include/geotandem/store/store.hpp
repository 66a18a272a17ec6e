#pragma once
// The component store (design section 7; the seed's "raw data file + index component file"):
//   STORE/store.json     format version, cube geometry, creation info
//   STORE/index.sqlite   one row per component (key, record location, measures, run), runs and
//                        named selections; written by one process (the manager, or the single
//                        process of a local run)
//   STORE/shards/*.gts   append-only raw data, one shard per writer (see shard.hpp)
// An index row is committed only after its record was made durable, so every row points at a
// complete record, whatever moment a process is killed. The byte layout is in docs/store-format.md.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geotandem/mesh/component.hpp"
#include "geotandem/store/query.hpp"
#include "geotandem/store/shard.hpp"
#include "geotandem/volume/geometry.hpp"

namespace geotandem::store {

inline constexpr int store_format_version = 1;

// What the index holds for one component. Measures are in world units (see mesh::ComponentStats);
// the vertex and triangle counts of `stats` are those of the stored record.
struct ComponentRow {
  std::uint64_t key = 0;
  RecordLocation location;
  mesh::ComponentStats stats;
  std::optional<std::int64_t> run;
  // The row's checksum as stored (docs/store-format.md); none in rows written before row checksums.
  // read() verifies it.
  std::optional<std::uint64_t> row_checksum;
  // Whether stats.samples was counted (rows written before volumes in samples hold none).
  bool samples_counted = false;
};

// A row to commit: a record already written (and synced) by a ShardWriter, with its measures.
struct IndexEntry {
  std::uint64_t key = 0;
  RecordLocation location;
  mesh::ComponentStats stats; // its counts are replaced by the location's
  std::optional<std::int64_t> run;
  // Replace the row of this key (its record was found damaged and was written again) instead of
  // leaving an existing row as it is.
  bool replace = false;
};

struct RunInfo {
  std::int64_t id = 0;
  std::string parameters; // JSON text given to begin_run
  std::string started;    // UTC, ISO 8601
  std::string ended;      // empty while the run is open (or was killed)
  std::string statistics; // JSON text given to end_run ("{}" before)
  std::uint64_t component_count = 0;
};

struct Selection {
  std::string name;
  std::string parameters;          // JSON text: what made the selection
  std::string created;             // UTC, ISO 8601
  std::vector<std::uint64_t> keys; // in the order they were saved (a ranking stays a ranking)
};

struct SelectionSummary {
  std::string name;
  std::string parameters;
  std::string created;
  std::uint64_t size = 0;
};

struct CreateOptions {
  std::string description; // free text kept in store.json
  std::string creator;     // the command line or program that made the store
};

enum class OpenMode { read_only, read_write };

// Not thread-safe: use one object per thread (SQLite allows concurrent readers of one store, and
// readers while one process writes).
class ComponentStore {
public:
  // Makes a new store in `dir` (created if missing; it must be empty otherwise). Throws
  // InvalidArgument for an invalid geometry or a directory that already holds files, IoError when
  // the directory cannot be written.
  static ComponentStore create(const std::filesystem::path& dir, const volume::Geometry& geometry,
                               const CreateOptions& options = {});
  // Opens an existing store. Throws IoError when `dir` does not exist, FormatError when it is not a
  // store (no store.json, unreadable JSON, a newer format version, a damaged index).
  static ComponentStore open(const std::filesystem::path& dir, OpenMode mode = OpenMode::read_only);
  // Opens the store in `dir` for writing if there is one (its grid must equal `geometry`'s, else
  // InvalidArgument; so must its CRS when both have one), creates it otherwise. Used to resume an
  // interrupted run. A store without a CRS takes the CRS of `geometry`.
  static ComponentStore open_or_create(const std::filesystem::path& dir, const volume::Geometry& geometry,
                                       const CreateOptions& options = {});
  // True when `dir` holds a store.json.
  static bool exists(const std::filesystem::path& dir);
  // Deletes the store in `dir` (for --fresh). Takes the store's writer lock first: throws IoError
  // when another process has the store open for writing (nothing is deleted then), or when `dir`
  // holds files that are not a store's. A missing `dir` is not an error.
  static void remove(const std::filesystem::path& dir);

  ~ComponentStore();
  ComponentStore(ComponentStore&&) noexcept;
  ComponentStore& operator=(ComponentStore&&) noexcept;

  const std::filesystem::path& directory() const;
  // The cube's geometry, with the CRS of its map coordinates (geometry().crs; empty in stores made
  // without one, which show "no CRS given").
  const volume::Geometry& geometry() const;
  // Keeps `crs` in store.json (replaced atomically). open_or_create calls it for a store made
  // without one. Throws InvalidArgument for a read-only store, IoError when store.json cannot be
  // written.
  void record_crs(const volume::Crs& crs);
  // The whole store.json as text.
  std::string info_json() const;
  bool writable() const;
  // False for an index written before row checksums (docs/store-format.md): its rows cannot be
  // verified. Opened for writing, the column is added; rows written from then on carry one.
  bool has_row_checksums() const;

  // Runs. `parameters_json` and `statistics_json` must be JSON (InvalidArgument otherwise).
  // Parameters holding an "identity" object (what decides the components: isovalue, extraction
  // settings, input fingerprint, attribute chain) are checked against the identity of the store's
  // earlier runs: a different one throws InvalidArgument listing every difference, so that two
  // extractions are never mixed in one store (see resume_differences).
  std::int64_t begin_run(const std::string& parameters_json);
  // The differences between `identity` (a JSON object) and the identity the store's latest run
  // recorded, one readable line each ("iso: 0.5 in the store, 0.6 now"); empty when they agree or
  // when no run recorded an identity.
  std::vector<std::string> resume_differences(const std::string& identity_json) const;
  void end_run(std::int64_t run, const std::string& statistics_json);
  std::vector<RunInfo> runs() const;

  // Commits index rows in one transaction. A key already in the index is left as it is (a
  // component committed twice is stored once), unless the entry says `replace`. Returns the number of rows added. The
  // records must be durable already (ShardWriter::sync). Throws InvalidArgument for an invalid shard name, IoError when
  // the index cannot be written (read-only store, disk full).
  std::size_t commit(const std::vector<IndexEntry>& entries);
  std::size_t commit(const IndexEntry& entry) { return commit(std::vector<IndexEntry>{entry}); }

  // contains() and find() each keep one prepared statement between calls (a local sink asks for
  // every component it commits).
  bool contains(std::uint64_t key) const;
  // The keys among `keys` already in the index, in the order given (one statement for all: the
  // manager checks each batch its workers commit).
  std::vector<std::uint64_t> present(const std::vector<std::uint64_t>& keys) const;
  std::uint64_t size() const;
  // The end of the last indexed record of a shard (0 when the shard has none).
  std::uint64_t indexed_end(const std::string& shard) const;

  // Index rows matching `query`, in its order. Throws InvalidArgument for an unknown selection or
  // an inconsistent range (min above max).
  std::vector<ComponentRow> query(const Query& query = {}) const;
  // The number of rows matching the filters of `query` (its sort and limit are ignored).
  std::uint64_t count(const Query& query) const;
  // The row of one key; std::nullopt when absent.
  std::optional<ComponentRow> find(std::uint64_t key) const;
  // Reads a component's surface in world coordinates, verifying the row's checksum (when it has
  // one) and the record's. Throws InvalidArgument for an unknown key, IoError for a missing shard,
  // FormatError (naming shard, offset and key, or the index for a changed row) for a damaged
  // record or row.
  mesh::SurfaceMesh read(std::uint64_t key) const;
  mesh::SurfaceMesh read(const ComponentRow& row) const;

  // Named selections: a list of keys with the parameters that chose it (bubble removal writes one
  // instead of deleting components; azimuth sorting writes a ranking). The order is kept (a key
  // given twice keeps its first place). Every key must be in the store (InvalidArgument naming
  // the first missing one). An existing selection of that name is replaced only with `replace`.
  void save_selection(const std::string& name, const std::vector<std::uint64_t>& keys,
                      const std::string& parameters_json, bool replace = false);
  Selection load_selection(const std::string& name) const;
  std::vector<SelectionSummary> selections() const;
  void delete_selection(const std::string& name);

private:
  struct Impl;
  explicit ComponentStore(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

} // namespace geotandem::store
