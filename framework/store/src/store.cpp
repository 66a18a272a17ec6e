// Creating and opening stores, store.json, runs.

#include <unistd.h>

#include <cerrno>
#include <set>

#include "geotandem/core/error.hpp"
#include "store_impl.hpp"

#ifndef GEOTANDEM_VERSION
#define GEOTANDEM_VERSION "unknown"
#endif

namespace geotandem::store {

using namespace detail;

namespace {

constexpr const char* format_name = "geotandem component store";

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

std::filesystem::path info_path(const std::filesystem::path& dir) {
  return dir / "store.json";
}

std::filesystem::path index_path(const std::filesystem::path& dir) {
  return dir / "index.sqlite";
}

// True when `dir` holds nothing but what an interrupted create() leaves: an index, its journal
// files, store.json.tmp and an empty shards/ directory. Such a directory was never a store.
bool is_interrupted_creation(const std::filesystem::path& dir) {
  static const std::set<std::string> leftovers = {"index.sqlite",         "index.sqlite-wal", "index.sqlite-shm",
                                                  "index.sqlite-journal", "store.json.tmp",   "shards"};
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    auto name = entry.path().filename().string();
    if (!leftovers.count(name) && !is_store_json_temporary(name)) return false;
    if (name == "shards" && !(entry.is_directory() && std::filesystem::is_empty(entry.path(), ec))) return false;
  }
  return !ec;
}

// A store opened for writing whose directory, index or shards/ this user may not write is refused
// here, naming the file: SQLite only said "attempt to write a readonly database" at the first
// commit, without the file or the cause.
void require_writable_files(const std::filesystem::path& dir) {
  for (const auto& path : {dir, index_path(dir), dir / "shards"}) {
    if (::access(path.c_str(), W_OK) == 0 || errno == ENOENT) continue;
    const int error = errno;
    throw IoError("cannot write the store: " + path.filename().string() + " is read-only for this user (" +
                      errno_text(error) + ")",
                  {path.string()},
                  "make the store writable (chmod -R u+w on the store directory), or write to another output "
                  "directory; reading it ('geotandem store ls', 'check', 'export') works as it is");
  }
}

} // namespace

ComponentStore::ComponentStore(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ComponentStore::~ComponentStore() = default;
ComponentStore::ComponentStore(ComponentStore&&) noexcept = default;
ComponentStore& ComponentStore::operator=(ComponentStore&&) noexcept = default;

bool ComponentStore::exists(const std::filesystem::path& dir) {
  std::error_code ec;
  return std::filesystem::is_regular_file(info_path(dir), ec);
}

ComponentStore ComponentStore::create(const std::filesystem::path& dir, const volume::Geometry& geometry,
                                      const CreateOptions& options) {
  geometry.validate();
  std::error_code ec;
  if (exists(dir))
    throw InvalidArgument("a store already exists here", {dir.string()}, "open it, or remove it to start afresh");
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
    throw InvalidArgument("cannot create a store: the path is a file", {dir.string()});
  std::filesystem::create_directories(dir, ec);
  if (ec) throw IoError("cannot create the store directory: " + ec.message(), {dir.string()});
  // Created under an exclusive lock, and everything is checked again under it: two processes
  // starting on one new output directory would otherwise both build the index, or one would take
  // the other's half-made store for an interrupted creation and delete it.
  FileHandle creating = lock_store_directory(dir);
  if (exists(dir))
    throw IoError("another process has just created a store here", {dir.string()},
                  "wait until it ends and run again to resume it, or write to another output directory");
  if (!std::filesystem::is_empty(dir, ec) && is_interrupted_creation(dir)) {
    for (const auto& entry : std::filesystem::directory_iterator(dir))
      std::filesystem::remove_all(entry.path());
  } else if (!std::filesystem::is_empty(dir, ec)) {
    throw InvalidArgument("cannot create a store in a directory that is not empty", {dir.string()},
                          "name a new or empty directory");
  }
  std::filesystem::create_directories(dir / "shards", ec);
  if (ec) throw IoError("cannot create the store directory: " + ec.message(), {dir.string()});

  auto impl = std::make_unique<Impl>();
  impl->dir = dir;
  impl->geometry = geometry;
  impl->writable = true;
  impl->db = std::make_unique<Database>(index_path(dir).string(), true, false);
  configure_connection(*impl->db, true);
  create_schema(*impl->db);

  nlohmann::json info = {{"format", format_name},
                         {"format_version", store_format_version},
                         {"geometry", geometry_to_json(geometry)},
                         {"created",
                          {{"time", utc_now()},
                           {"host", host_name()},
                           {"creator", options.creator},
                           {"geotandem_version", GEOTANDEM_VERSION}}},
                         {"description", options.description}};
  impl->info_json = info.dump(2) + "\n";
  // store.json comes last: a directory without it is an interrupted creation, never a store.
  sync_directory(dir);
  write_file_atomically(info_path(dir), impl->info_json);
  // Held on as the writer's lock, as when a store is opened for writing.
  impl->writer_lock = std::move(creating);
  return ComponentStore(std::move(impl));
}

ComponentStore ComponentStore::open(const std::filesystem::path& dir, OpenMode mode) {
  std::error_code ec;
  if (!std::filesystem::exists(dir, ec)) throw IoError("no such store directory", {dir.string()});
  if (!std::filesystem::is_directory(dir, ec))
    throw FormatError("not a geotandem store: a file, not a directory", {dir.string()});
  if (!exists(dir))
    throw FormatError("not a geotandem store: no store.json in the directory", {dir.string()},
                      "give the directory made by 'geotandem extract' or a recipe's store output");
  const auto info_file = info_path(dir).string();
  auto text = read_text_file(info_path(dir));
  auto info = nlohmann::json::parse(text, nullptr, false);
  if (info.is_discarded() || !info.is_object()) throw FormatError("store.json is not valid JSON", {info_file});
  if (info.value("format", std::string()) != format_name)
    throw FormatError("store.json does not describe a geotandem component store", {info_file});
  if (!info.contains("format_version") || !info["format_version"].is_number_integer())
    throw FormatError("store.json has no format_version", {info_file});
  int version = info["format_version"].get<int>();
  if (version > store_format_version || version < 1)
    throw FormatError("the store has format version " + std::to_string(version) + "; this build reads version " +
                          std::to_string(store_format_version),
                      {info_file}, "use the geotandem version that wrote it");
  if (!info.contains("geometry")) throw FormatError("store.json has no geometry", {info_file});

  auto impl = std::make_unique<Impl>();
  impl->dir = dir;
  impl->geometry = geometry_from_json(info["geometry"], info_file);
  impl->info_json = text;
  impl->writable = mode == OpenMode::read_write;
  if (!std::filesystem::is_regular_file(index_path(dir), ec))
    throw FormatError("the store has no index.sqlite", {dir.string()}, "the store is incomplete or damaged");
  if (impl->writable) impl->writer_lock = lock_store_directory(dir);
  if (impl->writable) require_writable_files(dir);
  // A store on read-only media or in a directory this user may not write, whose index has no
  // write-ahead log to replay: opened as immutable, since SQLite could not make the WAL's
  // shared-memory file there. With a log (a writer was killed), the ordinary read-only open reads
  // it through the shared-memory file the writer left.
  std::error_code wal_ec;
  const auto wal = std::filesystem::path(index_path(dir).string() + "-wal");
  const bool has_log = std::filesystem::exists(wal, wal_ec) && std::filesystem::file_size(wal, wal_ec) > 0;
  const bool immutable =
      !impl->writable && !has_log && (::access(dir.c_str(), W_OK) != 0 || ::access(index_path(dir).c_str(), W_OK) != 0);
  impl->db = std::make_unique<Database>(index_path(dir).string(), false, !impl->writable, immutable);
  configure_connection(*impl->db, impl->writable);
  check_schema(*impl->db);
  impl->cap_columns = upgrade_cap_columns(*impl->db, impl->writable);
  impl->row_checksums = upgrade_row_checksum_column(*impl->db, impl->writable);
  impl->samples_column = upgrade_samples_column(*impl->db, impl->writable);
  return ComponentStore(std::move(impl));
}

ComponentStore ComponentStore::open_or_create(const std::filesystem::path& dir, const volume::Geometry& geometry,
                                              const CreateOptions& options) {
  if (!exists(dir)) return create(dir, geometry, options);
  auto store = open(dir, OpenMode::read_write);
  if (!store.geometry().same_grid(geometry))
    throw InvalidArgument("the store was made for a cube of another geometry", {dir.string()},
                          "write to a new store, or extract from the cube the store was made for");
  // The CRS does not change the components, but a store has one: a run that names another is
  // refused; one that names none keeps the store's; a store made before CRSs were kept takes the
  // run's.
  const volume::Crs& kept = store.geometry().crs;
  if (!geometry.crs.empty() && !kept.empty() && !(kept == geometry.crs))
    throw InvalidArgument("the store's CRS is " + kept.label() + ", this run's is " + geometry.crs.label(),
                          {dir.string()},
                          "give the store's CRS (--crs, input.crs), write to another store, or pass --fresh to "
                          "replace the store");
  if (kept.empty() && !geometry.crs.empty()) store.record_crs(geometry.crs);
  return store;
}

const std::filesystem::path& ComponentStore::directory() const {
  return impl_->dir;
}
const volume::Geometry& ComponentStore::geometry() const {
  return impl_->geometry;
}

void ComponentStore::record_crs(const volume::Crs& crs) {
  impl_->require_writable("record a CRS");
  auto info = nlohmann::json::parse(impl_->info_json, nullptr, false);
  if (info.is_discarded() || !info.is_object() || !info.contains("geometry"))
    throw FormatError("store.json is not valid JSON", {info_path(impl_->dir).string()});
  volume::Geometry geometry = impl_->geometry;
  geometry.crs = crs;
  info["geometry"] = geometry_to_json(geometry);
  const std::string text = info.dump(2) + "\n";
  write_file_atomically(info_path(impl_->dir), text);
  impl_->info_json = text;
  impl_->geometry = geometry;
}
std::string ComponentStore::info_json() const {
  return impl_->info_json;
}
bool ComponentStore::writable() const {
  return impl_->writable;
}
bool ComponentStore::has_row_checksums() const {
  return impl_->row_checksums;
}

void ComponentStore::Impl::require_writable(const char* what) const {
  if (!writable)
    throw InvalidArgument(std::string("cannot ") + what + ": the store is open read-only", {dir.string()},
                          "open it with OpenMode::read_write");
}

const FileHandle& ComponentStore::Impl::shard_for_reading(const std::string& shard) {
  auto it = shards.find(shard);
  if (it == shards.end()) it = shards.emplace(shard, open_read(shard_path(dir, shard))).first;
  return it->second;
}

void ComponentStore::end_run(std::int64_t run, const std::string& statistics_json) {
  impl_->require_writable("end a run");
  auto statistics = parse_json_argument(statistics_json, "the run statistics");
  auto& db = *impl_->db;
  db.prepare("UPDATE runs SET ended = ?, statistics = ? WHERE id = ?")
      .bind(1, utc_now())
      .bind(2, statistics.dump())
      .bind(3, run)
      .run();
  if (db.changes() != 1)
    throw InvalidArgument("no run " + std::to_string(run) + " in the store", {impl_->dir.string()});
}

std::vector<RunInfo> ComponentStore::runs() const {
  auto statement =
      impl_->db->prepare("SELECT r.id, r.parameters, r.started, r.ended, r.statistics,"
                         " (SELECT count(*) FROM components c WHERE c.run = r.id) FROM runs r ORDER BY r.id");
  std::vector<RunInfo> runs;
  while (statement.step()) {
    RunInfo run;
    run.id = statement.column_int(0);
    run.parameters = statement.column_text(1);
    run.started = statement.column_text(2);
    run.ended = statement.column_text(3);
    run.statistics = statement.column_text(4);
    run.component_count = from_sql(statement.column_int(5));
    runs.push_back(std::move(run));
  }
  return runs;
}

} // namespace geotandem::store
