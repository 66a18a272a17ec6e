#pragma once
// A thin RAII layer over the SQLite C API for the store's index. Every failure becomes an IoError or
// FormatError naming the database file and the statement that failed.

#include <sqlite3.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace geotandem::store::detail {

class Statement;

class Database {
public:
  // Opens (and with `create`, creates) the database file. `read_only` opens it without write access.
  // `immutable`: the file cannot change while open (read-only media); SQLite then takes no locks and
  // makes no WAL shared-memory file.
  Database(const std::string& path, bool create, bool read_only, bool immutable = false);
  ~Database();
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  // Runs one or more statements that return no rows.
  void exec(const std::string& sql);
  Statement prepare(std::string_view sql);
  std::int64_t changes() const { return sqlite3_changes64(db_); }
  const std::string& path() const { return path_; }
  sqlite3* handle() const { return db_; }

  // Throws the error SQLite reports for `what` (IoError for I/O and locking, FormatError for a file
  // that is not a database or is corrupt).
  [[noreturn]] void fail(int code, const std::string& what) const;

private:
  sqlite3* db_ = nullptr;
  std::string path_;
};

// A prepared statement. Bind parameters are 1-based as in SQLite; columns are 0-based.
class Statement {
public:
  Statement(const Database& db, std::string_view sql);
  ~Statement();
  Statement(Statement&& other) noexcept;
  Statement& operator=(Statement&&) = delete;
  Statement(const Statement&) = delete;

  Statement& bind(int index, std::int64_t value);
  Statement& bind(int index, double value);
  Statement& bind(int index, const std::string& value);
  Statement& bind_null(int index);
  Statement& bind(int index, const std::optional<std::int64_t>& value) {
    return value ? bind(index, *value) : bind_null(index);
  }

  int parameter_count() const { return sqlite3_bind_parameter_count(stmt_); }
  // Steps once: true while a row is available, false when done.
  bool step();
  // Steps to completion of a statement that returns no rows.
  void run() {
    while (step()) {
    }
  }
  void reset();

  std::int64_t column_int(int column) const { return sqlite3_column_int64(stmt_, column); }
  double column_double(int column) const { return sqlite3_column_double(stmt_, column); }
  std::string column_text(int column) const;
  bool column_is_null(int column) const { return sqlite3_column_type(stmt_, column) == SQLITE_NULL; }

private:
  const Database* db_;
  sqlite3_stmt* stmt_ = nullptr;
  std::string sql_;
};

// Begins a write transaction (BEGIN IMMEDIATE) and rolls it back unless commit() was called.
class Transaction {
public:
  explicit Transaction(Database& db);
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit();

private:
  Database& db_;
  bool done_ = false;
};

// Keys, checksums and counts are uint64 in the API and INTEGER (int64) in SQLite: stored bit for bit.
inline std::int64_t to_sql(std::uint64_t value) {
  return static_cast<std::int64_t>(value);
}
inline std::uint64_t from_sql(std::int64_t value) {
  return static_cast<std::uint64_t>(value);
}

} // namespace geotandem::store::detail
