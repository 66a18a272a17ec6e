#include "sqlite.hpp"

#include <cstdio>

#include "geotandem/core/error.hpp"

namespace geotandem::store::detail {
namespace {

bool is_format_problem(int code) {
  int primary = code & 0xff;
  return primary == SQLITE_NOTADB || primary == SQLITE_CORRUPT || primary == SQLITE_SCHEMA;
}

// The error for SQLite's `code`: what is wrong with the index, which file, and what to do, with
// SQLite's own words in parentheses (its "attempt to write a readonly database" alone named
// neither the file nor the cause).
[[noreturn]] void throw_index_error(int code, const std::string& sqlite_text, const std::string& what,
                                    const std::string& path) {
  const std::string said = " (" + what + ": " + sqlite_text + ", SQLite code " + std::to_string(code) + ")";
  const int primary = code & 0xff;
  if (is_format_problem(code))
    throw FormatError("the store index is damaged or is not a geotandem store index" + said, {path},
                      "restore index.sqlite from a copy; or replace the store (--fresh on extract or run-workflow) "
                      "and extract again");
  if (primary == SQLITE_READONLY) {
    if (code == SQLITE_READONLY_RECOVERY || code == SQLITE_READONLY_CANTINIT || code == SQLITE_READONLY_CANTLOCK)
      throw IoError("cannot read the store index: a killed writer left a write-ahead log (index.sqlite-wal) that "
                    "must be replayed, and this user cannot write the store directory" +
                        said,
                    {path}, "open the store once as a user who may write its directory, or copy the store elsewhere");
    throw IoError("cannot write the store index: the file or the store directory is read-only for this user" + said,
                  {path},
                  "make the store directory and index.sqlite writable (chmod u+w), or write to another output "
                  "directory");
  }
  if (primary == SQLITE_FULL)
    throw IoError("cannot write the store index: the disk is full" + said, {path}, "free some space and run again");
  if (primary == SQLITE_CANTOPEN)
    throw IoError("cannot open the store index" + said, {path},
                  "check that the store directory and index.sqlite exist and that this user may read and write them");
  throw IoError("the store index failed" + said, {path});
}

} // namespace

Database::Database(const std::string& path, bool create, bool read_only, bool immutable) : path_(path) {
  int flags = read_only ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE;
  if (create && !read_only) flags |= SQLITE_OPEN_CREATE;
  std::string name = path;
  if (immutable && read_only) {
    // A URI: reserved characters of the path are escaped.
    name = "file:";
    for (unsigned char c : path) {
      if (c == '%' || c == '?' || c == '#') {
        char hex[4];
        std::snprintf(hex, sizeof hex, "%%%02X", c);
        name += hex;
      } else {
        name += static_cast<char>(c);
      }
    }
    name += "?immutable=1";
    flags |= SQLITE_OPEN_URI;
  }
  int rc = sqlite3_open_v2(name.c_str(), &db_, flags | SQLITE_OPEN_NOMUTEX, nullptr);
  if (rc != SQLITE_OK) {
    std::string message = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    const int code = db_ ? sqlite3_extended_errcode(db_) : rc;
    sqlite3_close(db_);
    db_ = nullptr;
    throw_index_error(code, message, "opening it", path);
  }
  sqlite3_extended_result_codes(db_, 1);
  // Readers may meet a writer mid-commit: wait for it instead of failing at once.
  sqlite3_busy_timeout(db_, 10000);
}

Database::~Database() {
  sqlite3_close_v2(db_);
}

void Database::fail(int code, const std::string& what) const {
  throw_index_error(code, sqlite3_errmsg(db_), what, path_);
}

void Database::exec(const std::string& sql) {
  char* error = nullptr;
  int rc = sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error);
  if (rc != SQLITE_OK) {
    std::string text = error ? error : sqlite3_errstr(rc);
    sqlite3_free(error);
    throw_index_error(sqlite3_extended_errcode(db_), text, "in '" + sql.substr(0, 80) + "'", path_);
  }
}

Statement Database::prepare(std::string_view sql) {
  return Statement(*this, sql);
}

Statement::Statement(const Database& db, std::string_view sql) : db_(&db), sql_(sql) {
  int rc = sqlite3_prepare_v2(db.handle(), sql_.data(), static_cast<int>(sql_.size()), &stmt_, nullptr);
  if (rc != SQLITE_OK) db.fail(rc, "cannot prepare index statement '" + sql_.substr(0, 80) + "'");
}

Statement::~Statement() {
  sqlite3_finalize(stmt_);
}

Statement::Statement(Statement&& other) noexcept : db_(other.db_), stmt_(other.stmt_), sql_(std::move(other.sql_)) {
  other.stmt_ = nullptr;
}

Statement& Statement::bind(int index, std::int64_t value) {
  int rc = sqlite3_bind_int64(stmt_, index, value);
  if (rc != SQLITE_OK) db_->fail(rc, "cannot bind parameter " + std::to_string(index));
  return *this;
}

Statement& Statement::bind(int index, double value) {
  int rc = sqlite3_bind_double(stmt_, index, value);
  if (rc != SQLITE_OK) db_->fail(rc, "cannot bind parameter " + std::to_string(index));
  return *this;
}

Statement& Statement::bind(int index, const std::string& value) {
  int rc = sqlite3_bind_text(stmt_, index, value.data(), static_cast<int>(value.size()), SQLITE_TRANSIENT);
  if (rc != SQLITE_OK) db_->fail(rc, "cannot bind parameter " + std::to_string(index));
  return *this;
}

Statement& Statement::bind_null(int index) {
  int rc = sqlite3_bind_null(stmt_, index);
  if (rc != SQLITE_OK) db_->fail(rc, "cannot bind parameter " + std::to_string(index));
  return *this;
}

bool Statement::step() {
  int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  db_->fail(rc, "index statement failed '" + sql_.substr(0, 80) + "'");
}

void Statement::reset() {
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
}

std::string Statement::column_text(int column) const {
  const auto* text = sqlite3_column_text(stmt_, column);
  if (!text) return {};
  return std::string(reinterpret_cast<const char*>(text),
                     static_cast<std::size_t>(sqlite3_column_bytes(stmt_, column)));
}

Transaction::Transaction(Database& db) : db_(db) {
  db_.exec("BEGIN IMMEDIATE");
}

Transaction::~Transaction() {
  if (!done_) sqlite3_exec(db_.handle(), "ROLLBACK", nullptr, nullptr, nullptr);
}

void Transaction::commit() {
  db_.exec("COMMIT");
  done_ = true;
}

} // namespace geotandem::store::detail
