#include "storage/sqlite_handle.h"

namespace alignset::storage {

int64_t SqliteMemoryUsed() { return sqlite3_memory_used(); }
int64_t SqliteMemoryPeak() { return sqlite3_memory_highwater(/*resetFlag=*/0); }

Status SqliteError(int rc, sqlite3* db, std::string_view what) {
  std::string msg(what);
  msg += ": ";
  // The connection's message is more specific, but only while it still
  // describes this error code.
  if (db != nullptr && (sqlite3_errcode(db) & 0xff) == (rc & 0xff)) {
    msg += sqlite3_errmsg(db);
  } else {
    msg += sqlite3_errstr(rc);
  }
  switch (rc & 0xff) {
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
      return Status::Unavailable(msg);
    case SQLITE_CORRUPT:
    case SQLITE_NOTADB:
      return Status::DataLoss(msg);
    case SQLITE_FULL:
    case SQLITE_TOOBIG:
    case SQLITE_NOMEM:
      return Status::ResourceExhausted(msg);
    case SQLITE_CANTOPEN:
      return Status::NotFound(msg);
    case SQLITE_READONLY:
    case SQLITE_CONSTRAINT:
    case SQLITE_RANGE:
      return Status::InvalidArgument(msg);
    default:
      return Status::Internal(msg);
  }
}

StatusOr<Db> Db::Open(const std::string& path, int flags, int busy_timeout_ms) {
  sqlite3* raw = nullptr;
  const int rc = sqlite3_open_v2(path.c_str(), &raw, flags, nullptr);
  Db db;
  db.db_ = raw;  // even on failure sqlite3_open_v2 may allocate a handle
  if (rc != SQLITE_OK) return SqliteError(rc, raw, "open " + path);
  sqlite3_extended_result_codes(raw, 1);
  sqlite3_busy_timeout(raw, busy_timeout_ms);
  return db;
}

Db& Db::operator=(Db&& o) noexcept {
  if (this != &o) {
    if (db_ != nullptr) sqlite3_close_v2(db_);
    db_ = o.db_;
    o.db_ = nullptr;
  }
  return *this;
}

Db::~Db() {
  if (db_ != nullptr) sqlite3_close_v2(db_);
}

Status Db::Exec(std::string_view sql) const {
  const std::string text(sql);
  const int rc = sqlite3_exec(db_, text.c_str(), nullptr, nullptr, nullptr);
  if (rc != SQLITE_OK) return SqliteError(rc, db_, text);
  return Status::Ok();
}

StatusOr<std::string> Db::QueryText(std::string_view sql) const {
  auto stmt = Stmt::Prepare(db_, sql);
  if (!stmt.ok()) return stmt.status();
  auto row = stmt->Step();
  if (!row.ok()) return row.status();
  if (!*row) return Status::Internal(std::string(sql) + ": no row");
  return stmt->Text(0);
}

StatusOr<Stmt> Stmt::Prepare(sqlite3* db, std::string_view sql) {
  Stmt s;
  s.db_ = db;
  const int rc = sqlite3_prepare_v2(db, sql.data(), static_cast<int>(sql.size()), &s.stmt_, nullptr);
  if (rc != SQLITE_OK) return SqliteError(rc, db, "prepare '" + std::string(sql) + "'");
  return s;
}

Stmt& Stmt::operator=(Stmt&& o) noexcept {
  if (this != &o) {
    if (stmt_ != nullptr) sqlite3_finalize(stmt_);
    db_ = o.db_;
    stmt_ = o.stmt_;
    bind_rc_ = o.bind_rc_;
    o.stmt_ = nullptr;
  }
  return *this;
}

Stmt::~Stmt() {
  if (stmt_ != nullptr) sqlite3_finalize(stmt_);
}

void Stmt::BindInt(int i, int64_t v) { NoteBind(sqlite3_bind_int64(stmt_, i, v)); }
void Stmt::BindDouble(int i, double v) { NoteBind(sqlite3_bind_double(stmt_, i, v)); }
void Stmt::BindNull(int i) { NoteBind(sqlite3_bind_null(stmt_, i)); }
void Stmt::BindText(int i, std::string_view v) {
  NoteBind(sqlite3_bind_text64(stmt_, i, v.data(), v.size(), SQLITE_TRANSIENT, SQLITE_UTF8));
}
void Stmt::BindBlob(int i, std::span<const uint8_t> v) {
  // SQLITE_STATIC: the caller's buffer outlives the Step that reads it, and a
  // 16 MiB set should not be copied once more.
  NoteBind(sqlite3_bind_blob64(stmt_, i, v.data(), v.size(), SQLITE_STATIC));
}

StatusOr<bool> Stmt::Step() {
  if (bind_rc_ != SQLITE_OK) return SqliteError(bind_rc_, db_, "bind");
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  return SqliteError(rc, db_, sqlite3_sql(stmt_));
}

Status Stmt::Run() {
  for (;;) {
    auto row = Step();
    if (!row.ok()) return row.status();
    if (!*row) return Status::Ok();
  }
}

std::string Stmt::Text(int col) const {
  const unsigned char* p = sqlite3_column_text(stmt_, col);
  const int len = sqlite3_column_bytes(stmt_, col);
  return p == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(p), len);
}

std::span<const uint8_t> Stmt::Blob(int col) const {
  const void* p = sqlite3_column_blob(stmt_, col);
  const int len = sqlite3_column_bytes(stmt_, col);
  if (p == nullptr) return {};
  return {static_cast<const uint8_t*>(p), static_cast<size_t>(len)};
}

StatusOr<Transaction> Transaction::Begin(const Db& db, Kind kind) {
  Status s = db.Exec(kind == Kind::kWrite ? "BEGIN IMMEDIATE" : "BEGIN");
  if (!s.ok()) return s;
  return Transaction(&db);
}

Transaction::~Transaction() {
  // After a failed COMMIT or a failed statement SQLite may already have
  // rolled back; only roll back a transaction that is still open.
  if (db_ != nullptr && !sqlite3_get_autocommit(db_->get())) {
    sqlite3_exec(db_->get(), "ROLLBACK", nullptr, nullptr, nullptr);
  }
}

Status Transaction::Commit() {
  const Db* db = db_;
  Status s = db->Exec("COMMIT");
  if (s.ok()) db_ = nullptr;
  return s;
}

}  // namespace alignset::storage
