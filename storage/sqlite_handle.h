#pragma once

#include <sqlite3.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "core/util/status.h"

namespace alignset::storage {

// Maps an SQLite result code onto a Status: busy/locked -> Unavailable (the
// caller may retry), corrupt/not-a-database -> DataLoss, disk full / too big
// -> ResourceExhausted, cannot open -> NotFound, anything else -> Internal.
Status SqliteError(int rc, sqlite3* db, std::string_view what);

// SQLite's own allocations in this process (every connection: page caches,
// statements, schema), now and at their highest since start.
int64_t SqliteMemoryUsed();
int64_t SqliteMemoryPeak();

// Owns one connection; closes it on destruction.
class Db {
 public:
  Db() = default;
  // `flags`: SQLITE_OPEN_* flags. Sets the busy timeout before anything else
  // so that even the first statement waits for other writers.
  static StatusOr<Db> Open(const std::string& path, int flags, int busy_timeout_ms);
  Db(Db&& o) noexcept : db_(o.db_) { o.db_ = nullptr; }
  Db& operator=(Db&& o) noexcept;
  Db(const Db&) = delete;
  Db& operator=(const Db&) = delete;
  ~Db();

  sqlite3* get() const { return db_; }
  // Runs one or more statements that return no rows of interest.
  Status Exec(std::string_view sql) const;
  // The single text value of a one-row query (e.g. a PRAGMA).
  StatusOr<std::string> QueryText(std::string_view sql) const;

 private:
  sqlite3* db_ = nullptr;
};

// Owns one prepared statement. Bind errors are remembered and reported by the
// next Step, so call sites bind without checking each call.
class Stmt {
 public:
  Stmt() = default;
  static StatusOr<Stmt> Prepare(sqlite3* db, std::string_view sql);
  Stmt(Stmt&& o) noexcept : db_(o.db_), stmt_(o.stmt_), bind_rc_(o.bind_rc_) { o.stmt_ = nullptr; }
  Stmt& operator=(Stmt&& o) noexcept;
  Stmt(const Stmt&) = delete;
  Stmt& operator=(const Stmt&) = delete;
  ~Stmt();

  // Parameters are 1-based, as in SQLite.
  void BindInt(int i, int64_t v);
  void BindDouble(int i, double v);
  void BindText(int i, std::string_view v);
  void BindBlob(int i, std::span<const uint8_t> v);
  void BindNull(int i);

  // true: a row is ready; false: done.
  StatusOr<bool> Step();
  // Steps to completion and expects no row.
  Status Run();

  int64_t Int(int col) const { return sqlite3_column_int64(stmt_, col); }
  double Double(int col) const { return sqlite3_column_double(stmt_, col); }
  bool IsNull(int col) const { return sqlite3_column_type(stmt_, col) == SQLITE_NULL; }
  std::string Text(int col) const;
  // Valid until the next Step or the statement's destruction.
  std::span<const uint8_t> Blob(int col) const;

 private:
  void NoteBind(int rc) {
    if (bind_rc_ == SQLITE_OK) bind_rc_ = rc;
  }
  sqlite3* db_ = nullptr;
  sqlite3_stmt* stmt_ = nullptr;
  int bind_rc_ = SQLITE_OK;
};

// BEGIN (IMMEDIATE for writers, so a writer waits for the lock up front
// instead of failing to upgrade a read lock mid-transaction); rolls back on
// destruction unless committed.
class Transaction {
 public:
  enum class Kind { kRead, kWrite };
  static StatusOr<Transaction> Begin(const Db& db, Kind kind);
  Transaction() = default;
  Transaction(Transaction&& o) noexcept : db_(o.db_) { o.db_ = nullptr; }
  Transaction& operator=(Transaction&&) = delete;
  Transaction(const Transaction&) = delete;
  ~Transaction();
  Status Commit();

 private:
  explicit Transaction(const Db* db) : db_(db) {}
  const Db* db_ = nullptr;
};

}  // namespace alignset::storage
